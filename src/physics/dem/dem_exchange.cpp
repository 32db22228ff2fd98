// DemSystem's particles across subdomains and periodic faces: wrapping into the periodic
// domain, removal and migration, the owned particles' sort by cell, and the ghosts (other
// ranks' particles and periodic images) built and refreshed through the halo.
#include "kernels/grow_view.hpp"
#include "kernels/particles/binning.hpp"
#include "mesh/particles/particle_migration.hpp"
#include "physics/dem/dem_system.hpp"

namespace amphora::physics::dem {

// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace dem_exchange_kernels {

/// v(i, ...) = v(perm(i), ...) for i < n, through `scratch` (grown as needed), for LayoutRight
/// Views of any rank: the inner extents of a row are contiguous. v keeps its storage.
template <class ExecSpace, class View, class Perm, class Scratch>
void permute_rows(const ExecSpace& exec, const View& v, const Perm& perm, int n, Scratch& scratch) {
  using T = typename View::value_type;
  size_t inner = 1;
  for (unsigned r = 1; r < View::rank; ++r) inner *= v.extent(r);
  kernels::grow_uninitialized(scratch, size_t(n) * inner * sizeof(T),
                              "amphora::dem::permute_scratch");
  T* tmp = reinterpret_cast<T*>(scratch.data());
  T* d = v.data();
  Kokkos::parallel_for(
      "amphora::dem::permute", kernels::RangePolicy<ExecSpace>(exec, 0, n), KOKKOS_LAMBDA(int i) {
        const size_t from = size_t(perm(i)) * inner, to = size_t(i) * inner;
        for (size_t k = 0; k < inner; ++k) tmp[to + k] = d[from + k];
      });
  Kokkos::parallel_for(
      "amphora::dem::permute_back", kernels::RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(int i) {
        for (size_t k = size_t(i) * inner; k < size_t(i + 1) * inner; ++k) d[k] = tmp[k];
      });
}

}  // namespace dem_exchange_kernels

template <class ExecSpace>
void DemSystem<ExecSpace>::wrap_periodic() {
  // A restart's first rebuild keeps the checkpoint's build positions and wraps nothing: the
  // run it continues wraps at its next rebuild, and so does the restart.
  const mesh::particles::PeriodicWrap wrap = decomposition_.wrap();
  if (!wrap.any() || keep_build_positions_) return;
  const auto x = p_.x;
  Kokkos::parallel_for(
      "amphora::dem::wrap_periodic", kernels::RangePolicy<ExecSpace>(exec_, 0, p_.n_owned),
      KOKKOS_LAMBDA(int i) {
        for (int d = 0; d < 3; ++d) x(i, d) = wrap(x(i, d), d);
      });
}

template <class ExecSpace>
void DemSystem<ExecSpace>::remove_and_migrate() {
  wrap_periodic();
  const int n = p_.n_owned;
  const auto x = p_.x;
  const auto lo = decomposition_.lo(comm_.rank());
  const auto hi = decomposition_.hi(comm_.rank());
  const auto dlo = config_.domain_lo, dhi = config_.domain_hi;
  const double l0 = lo[0], l1 = lo[1], l2 = lo[2], h0 = hi[0], h1 = hi[1], h2 = hi[2];
  // periodic directions: nobody leaves the domain (the infinite bounds never fail)
  const double inf = std::numeric_limits<double>::infinity();
  const auto& per = config_.periodic;
  const double d0 = per[0] ? -inf : dlo[0], d1 = per[1] ? -inf : dlo[1],
               d2 = per[2] ? -inf : dlo[2];
  const double e0 = per[0] ? inf : dhi[0], e1 = per[1] ? inf : dhi[1], e2 = per[2] ? inf : dhi[2];
  const bool top0 = hi[0] == dhi[0], top1 = hi[1] == dhi[1], top2 = hi[2] == dhi[2];
  int leaving = 0;
  Kokkos::parallel_reduce(
      "amphora::dem::count_leaving", kernels::RangePolicy<ExecSpace>(exec_, 0, n),
      KOKKOS_LAMBDA(int i, int& c) {
        const double a = x(i, 0), b = x(i, 1), z = x(i, 2);
        const bool in_domain = a >= d0 && a <= e0 && b >= d1 && b <= e1 && z >= d2 && z <= e2;
        const bool mine = a >= l0 && (a < h0 || (top0 && a <= h0)) && b >= l1 &&
                          (b < h1 || (top1 && b <= h1)) && z >= l2 && (z < h2 || (top2 && z <= h2));
        if (!in_domain || !mine) ++c;
      },
      leaving);
  if (!comm_.any(leaving > 0)) return;

  // Force and torque are not carried (but by redistribute): the force evaluation under way
  // zeroes them again.
  forces_zeroed_ = false;
  const mesh::particles::OwnerMap owner = decomposition_.owner_map();
  kernels::grow_uninitialized(destination_, n, "amphora::dem::destination");
  const auto dest = destination_;
  Kokkos::parallel_for(
      "amphora::dem::destination", kernels::RangePolicy<ExecSpace>(exec_, 0, n),
      KOKKOS_LAMBDA(int i) {
        const double a = x(i, 0), b = x(i, 1), z = x(i, 2);
        const bool in_domain = a >= d0 && a <= e0 && b >= d1 && b <= e1 && z >= d2 && z <= e2;
        dest(i) = in_domain ? owner(a, b, z) : -1;  // -1: removed, it left the domain
      });
  mesh::particles::ParticleMigration<ExecSpace> migration(exec_, decomposition_, dest, n,
                                                          migration_buffers_);
  const int m = migration.send(exec_, migrating_fields());
  p_.n_owned = 0;
  resize_owned(m);
  migration.receive(exec_, migrating_fields());
  p_.n_owned = m;
}

template <class ExecSpace>
mesh::particles::ParticleFields<ExecSpace> DemSystem<ExecSpace>::migrating_fields() const {
  mesh::particles::ParticleFields<ExecSpace> f;
  f.add(p_.x).add(p_.v).add(p_.omega).add(p_.radius).add(p_.mass).add(p_.inertia);
  f.add(p_.material).add(p_.gid).add(wall_shear_).add(rec_gid_).add(rec_shear_).add(x_build_);
  if (external_.extent(0) > 0) f.add(external_);
  if (carry_forces_) f.add(p_.force).add(p_.torque);
  return f;
}

template <class ExecSpace>
void DemSystem<ExecSpace>::sort_owned_by_cell() {
  const int n = p_.n_owned;
  if (n == 0) return;
  // The cells of the whole domain's grid (order_rows) over this subdomain, and gid order in a
  // cell: storage close to the order the force loop runs the rows in.
  const CellGrid global = row_cells();
  const auto lo = decomposition_.lo(comm_.rank());
  const auto hi = decomposition_.hi(comm_.rank());
  CellGrid grid = global;
  for (int d = 0; d < 3; ++d) {
    const int first = global.coord(lo[d], d), last = global.coord(hi[d], d);
    grid.lo[d] = global.lo[d] + first * global.h;
    grid.n[d] = last - first + 1;
  }
  kernels::particles::bin_points(exec_, grid, x_build_, n, p_.gid, bins_);
  const auto perm = bins_.permutation;
  auto& s = permute_scratch_;
  dem_exchange_kernels::permute_rows(exec_, p_.x, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, p_.v, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, p_.omega, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, p_.force, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, p_.torque, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, p_.radius, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, p_.mass, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, p_.inertia, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, p_.material, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, p_.gid, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, wall_shear_, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, rec_gid_, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, rec_shear_, perm, n, s);
  dem_exchange_kernels::permute_rows(exec_, x_build_, perm, n, s);
  if (external_.extent(0) > 0) dem_exchange_kernels::permute_rows(exec_, external_, perm, n, s);
}

template <class ExecSpace>
void DemSystem<ExecSpace>::build_ghosts() {
  using Halo = mesh::particles::ParticleHalo<ExecSpace>;
  p_.n_ghost = 0;
  const int n = p_.n_owned;
  // What a ghost needs, chosen where the lists are built (x_build_).
  p_.n_ghost = halo_.build(exec_, decomposition_, n, halo_width_, [&](int capacity) {
    p_.reserve(capacity);
    kernels::grow_preserving(x_build_, capacity);
    mesh::particles::ParticleFields<ExecSpace> record;
    record.add_position(p_.x).add(p_.v).add(p_.omega).add(p_.radius).add(p_.mass);
    record.add(p_.inertia).add(p_.material).add(p_.gid).add_position(x_build_);
    return typename Halo::Arrays{record, x_build_};
  });
}

template <class ExecSpace>
void DemSystem<ExecSpace>::forward_ghosts() {
  if (halo_.empty()) return;
  mesh::particles::ParticleFields<ExecSpace> moving;
  moving.add_position(p_.x).add(p_.v).add(p_.omega);
  halo_.forward(exec_, decomposition_, moving);
}

#define AMPHORA_DEM_EXCHANGE(E)                                                       \
  template void DemSystem<E>::wrap_periodic();                                        \
  template void DemSystem<E>::remove_and_migrate();                                   \
  template mesh::particles::ParticleFields<E> DemSystem<E>::migrating_fields() const; \
  template void DemSystem<E>::sort_owned_by_cell();                                   \
  template void DemSystem<E>::build_ghosts();                                         \
  template void DemSystem<E>::forward_ghosts();
AMPHORA_FOR_EACH_EXEC_SPACE(AMPHORA_DEM_EXCHANGE)

}  // namespace amphora::physics::dem
