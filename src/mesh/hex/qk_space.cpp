#include "mesh/hex/qk_space.hpp"

#include <stdexcept>
#include <string>

#include "kernels/spaces.hpp"
#include "kernels/sumfac/quadrature_1d.hpp"

namespace amphora::mesh::hex {

template <int dim, class ExecSpace>
QkSpace<dim, ExecSpace>::QkSpace(const StructuredHexMesh<dim>& mesh, int degree) : mesh_(mesh) {
  mesh.validate();
  if (degree < 1 || degree > max_qk_degree)
    throw std::invalid_argument("QkSpace: degree " + std::to_string(degree) +
                                " outside the supported range 1.." + std::to_string(max_qk_degree));
  bool periodic[3] = {false, false, false};
  for (int d = 0; d < dim; ++d) periodic[d] = mesh.periodic(d);
  lattice_ = kernels::sumfac::QkLattice<dim>::create(degree, mesh.cells.data(), periodic,
                                                     mesh.dirichlet_faces(),
                                                     kernels::sumfac::simd_width_v<ExecSpace>);
  lattice_.shared_faces = mesh.interface_faces();

  // Node coordinates: Gauss–Lobatto points in each cell of the box, then the deformation.
  const std::vector<double> gl = kernels::sumfac::gauss_lobatto(degree + 1).points;
  std::vector<std::vector<double>> x1d(dim);
  for (int d = 0; d < dim; ++d) {
    const double h = (mesh.upper[d] - mesh.lower[d]) / mesh.cells[d];
    x1d[d].resize(lattice_.nodes[d]);
    for (int c = 0; c < mesh.cells[d]; ++c)
      for (int i = 0; i <= degree; ++i) x1d[d][c * degree + i] = mesh.lower[d] + h * (c + gl[i]);
    x1d[d].back() = mesh.upper[d];
  }
  const long n_nodes = lattice_.n_nodes();
  coordinates_ =
      Vector(Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::QkSpace::coordinates"),
             dim * n_nodes);
  auto xh = Kokkos::create_mirror_view(coordinates_);
  std::vector<long> constrained;
  for (long node = 0; node < n_nodes; ++node) {
    int ijk[3] = {0, 0, 0};
    long rest = node;
    for (int d = 0; d < dim; ++d) {
      ijk[d] = static_cast<int>(rest % lattice_.nodes[d]);
      rest /= lattice_.nodes[d];
    }
    Point3 X{0.0, 0.0, 0.0};
    for (int d = 0; d < dim; ++d) X[d] = x1d[d][ijk[d]];
    const Point3 x = mesh.deformation ? mesh.deformation(X) : X;
    for (int d = 0; d < dim; ++d) xh(d * n_nodes + node) = x[d];
    bool wrapped = false;
    for (int d = 0; d < dim; ++d) wrapped = wrapped || (periodic[d] && ijk[d] == lattice_.dofs[d]);
    if (!wrapped && lattice_.constrained(ijk)) constrained.push_back(lattice_.dof_index(ijk));
  }
  Kokkos::deep_copy(coordinates_, xh);
  constrained_ =
      Kokkos::View<long*, memory_space>("amphora::QkSpace::constrained", constrained.size());
  auto ch = Kokkos::create_mirror_view(constrained_);
  for (std::size_t i = 0; i < constrained.size(); ++i) ch(i) = constrained[i];
  Kokkos::deep_copy(constrained_, ch);
}

template <int dim, class ExecSpace>
std::vector<double> QkSpace<dim, ExecSpace>::dof_points() const {
  const long n = n_dofs(), n_nodes = lattice_.n_nodes();
  auto xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), coordinates_);
  std::vector<double> p(static_cast<std::size_t>(dim) * n);
  for (long node = 0; node < n_nodes; ++node) {
    int ijk[3] = {0, 0, 0};
    long rest = node;
    bool wrapped = false;
    for (int d = 0; d < dim; ++d) {
      ijk[d] = static_cast<int>(rest % lattice_.nodes[d]);
      rest /= lattice_.nodes[d];
      wrapped = wrapped || (lattice_.periodic[d] && ijk[d] == lattice_.dofs[d]);
    }
    if (wrapped) continue;
    const long i = lattice_.dof_index(ijk);
    for (int d = 0; d < dim; ++d) p[d * n + i] = xh(d * n_nodes + node);
  }
  return p;
}

#define AMPHORA_QK_SPACE(E)     \
  template class QkSpace<2, E>; \
  template class QkSpace<3, E>;
AMPHORA_IF_SERIAL(AMPHORA_QK_SPACE(Kokkos::Serial))
AMPHORA_IF_OPENMP(AMPHORA_QK_SPACE(Kokkos::OpenMP))
AMPHORA_IF_CUDA(AMPHORA_QK_SPACE(Kokkos::Cuda))

}  // namespace amphora::mesh::hex
