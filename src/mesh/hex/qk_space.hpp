#pragma once
// Continuous Q_k on a StructuredHexMesh (k = 1..8, Gauss–Lobatto nodes): the DoF lattice, the
// node coordinates (deformation applied, so curved cells are isoparametric) and the
// constrained (Dirichlet) DoFs. Vectors with several components are blocked: component c of
// DoF i is entry c * n_dofs() + i.
#include <vector>

#include <Kokkos_Core.hpp>

#include "kernels/sumfac/qk_lattice.hpp"
#include "kernels/sumfac/simd.hpp"
#include "mesh/hex/structured_hex_mesh.hpp"

namespace amphora::mesh::hex {

inline constexpr int max_qk_degree = 8;

template <int dim, class ExecSpace>
class QkSpace {
 public:
  using memory_space = typename ExecSpace::memory_space;
  using Vector = Kokkos::View<double*, memory_space>;

  QkSpace(const StructuredHexMesh<dim>& mesh, int degree);

  const StructuredHexMesh<dim>& mesh() const { return mesh_; }
  int degree() const { return lattice_.degree; }
  const kernels::sumfac::QkLattice<dim>& lattice() const { return lattice_; }
  long n_dofs() const { return lattice_.n_dofs(); }
  /// Coordinates of the unwrapped node lattice, blocked: coords(d * n_nodes + node).
  const Vector& coordinates() const { return coordinates_; }
  /// Indices of the DoFs on Dirichlet faces, ascending.
  const Kokkos::View<long*, memory_space>& constrained_dofs() const { return constrained_; }

  /// Host vector of f at every DoF's node (interpolation into Q_k), `components` blocked.
  template <class F>
  std::vector<double> interpolate(const F& f, int components = 1) const;
  /// Physical position of each DoF (host), blocked by coordinate.
  std::vector<double> dof_points() const;

 private:
  StructuredHexMesh<dim> mesh_;
  kernels::sumfac::QkLattice<dim> lattice_;
  Vector coordinates_;
  Kokkos::View<long*, memory_space> constrained_;
};

template <int dim, class ExecSpace>
template <class F>
std::vector<double> QkSpace<dim, ExecSpace>::interpolate(const F& f, int components) const {
  const std::vector<double> p = dof_points();
  const long n = n_dofs();
  std::vector<double> v(static_cast<std::size_t>(n) * components);
  for (long i = 0; i < n; ++i) {
    Point3 x{0.0, 0.0, 0.0};
    for (int d = 0; d < dim; ++d) x[d] = p[d * n + i];
    for (int c = 0; c < components; ++c) v[c * n + i] = f(x, c);
  }
  return v;
}

}  // namespace amphora::mesh::hex
