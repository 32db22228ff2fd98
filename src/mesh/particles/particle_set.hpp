#pragma once
// Particles in structure-of-arrays Views: one View per quantity, vectors as [n][3] with the
// three components of a particle adjacent (one cache line per gather of a neighbour). Owned
// particles come first, ghosts (copies of other ranks' particles) after them.
#include <cstdint>
#include <string>

#include "kernels/spaces.hpp"

namespace amphora::mesh::particles {

template <class MemSpace>
struct ParticleSet {
  static_assert(kernels::is_memory_space_v<MemSpace>, "ParticleSet is templated on a memory space");
  using Vec = Kokkos::View<double* [3], Kokkos::LayoutRight, MemSpace>;
  using Scalar = Kokkos::View<double*, MemSpace>;
  using Int = Kokkos::View<int*, MemSpace>;
  using Id = Kokkos::View<std::int64_t*, MemSpace>;

  Vec x, v, omega, force, torque;
  Scalar radius, mass, inertia;
  Int material;
  Id gid;  ///< stable global id, unique over all ranks and the whole run
  int n_owned = 0;
  int n_ghost = 0;

  int size() const { return n_owned + n_ghost; }
  int capacity() const { return static_cast<int>(x.extent(0)); }

  explicit ParticleSet(int capacity = 0) { allocate(capacity); }

  /// Grows (never shrinks) the arrays to hold at least n particles, keeping the first size().
  void reserve(int n) {
    if (n <= capacity()) return;
    const int cap = std::max(n, capacity() + capacity() / 2);
    Kokkos::resize(x, cap);
    Kokkos::resize(v, cap);
    Kokkos::resize(omega, cap);
    Kokkos::resize(force, cap);
    Kokkos::resize(torque, cap);
    Kokkos::resize(radius, cap);
    Kokkos::resize(mass, cap);
    Kokkos::resize(inertia, cap);
    Kokkos::resize(material, cap);
    Kokkos::resize(gid, cap);
  }

 private:
  void allocate(int n) {
    x = Vec("amphora::ParticleSet::x", n);
    v = Vec("amphora::ParticleSet::v", n);
    omega = Vec("amphora::ParticleSet::omega", n);
    force = Vec("amphora::ParticleSet::force", n);
    torque = Vec("amphora::ParticleSet::torque", n);
    radius = Scalar("amphora::ParticleSet::radius", n);
    mass = Scalar("amphora::ParticleSet::mass", n);
    inertia = Scalar("amphora::ParticleSet::inertia", n);
    material = Int("amphora::ParticleSet::material", n);
    gid = Id("amphora::ParticleSet::gid", n);
  }
};

}  // namespace amphora::mesh::particles
