#pragma once
// Textbook finite-element assembly into an Eigen sparse matrix, for checking the matrix-free
// operators: basis functions and their gradients evaluated directly (products of 1D Lagrange
// polynomials) at every quadrature point, Jacobians from the node coordinates, element
// matrices by quadrature, Dirichlet rows and columns replaced by identity.
#include <Eigen/Sparse>

#include <cmath>
#include <vector>

#include "kernels/sumfac/quadrature_1d.hpp"
#include "mesh/hex/qk_space.hpp"
#include "solvers/matrix_free/cell_operator_kernel.hpp"

namespace amphora::test {

template <int dim, class Space>
Eigen::SparseMatrix<double> assemble_reference(const Space& space, solvers::OperatorKind kind,
                                               int n_q, bool gauss_lobatto,
                                               const std::vector<double>& field) {
  const auto& lat = space.lattice();
  const int k = lat.degree, np = k + 1;
  const std::vector<double> nodes = sumfac::gauss_lobatto(np).points;
  const sumfac::Quadrature1D q = gauss_lobatto ? sumfac::gauss_lobatto(n_q) : sumfac::gauss(n_q);
  const std::vector<double> val = sumfac::lagrange_values(nodes, q.points);
  const std::vector<double> der = sumfac::lagrange_derivatives(nodes, q.points);
  auto coords = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), space.coordinates());
  const long n_nodes = lat.n_nodes(), n = lat.n_dofs();
  int nd = 1, nqt = 1;
  for (int d = 0; d < dim; ++d) nd *= np, nqt *= n_q;
  std::vector<Eigen::Triplet<double>> triplets;
  int cell[3] = {0, 0, 0};
  const int n_cells = static_cast<int>(space.mesh().n_cells());
  std::vector<long> dof(nd), node(nd);
  std::vector<double> phi(nd), dphi(nd * dim), elem(nd * nd);
  for (int c = 0; c < n_cells; ++c) {
    int rest = c;
    for (int d = 0; d < dim; ++d) cell[d] = rest % lat.cells[d], rest /= lat.cells[d];
    for (int j = 0; j < nd; ++j) {
      int ijk[3] = {0, 0, 0}, r = j;
      for (int d = 0; d < dim; ++d) ijk[d] = cell[d] * k + r % np, r /= np;
      dof[j] = lat.constrained(ijk) ? -1 : lat.dof_index(ijk);
      node[j] = lat.node_index(ijk);
    }
    std::fill(elem.begin(), elem.end(), 0.0);
    for (int p = 0; p < nqt; ++p) {
      int qi[3] = {0, 0, 0}, r = p;
      double w = 1.0;
      for (int d = 0; d < dim; ++d) qi[d] = r % n_q, r /= n_q, w *= q.weights[qi[d]];
      for (int j = 0; j < nd; ++j) {
        int ji[3] = {0, 0, 0}, rj = j;
        for (int d = 0; d < dim; ++d) ji[d] = rj % np, rj /= np;
        phi[j] = 1.0;
        for (int d = 0; d < dim; ++d) phi[j] *= val[qi[d] * np + ji[d]];
        for (int e = 0; e < dim; ++e) {
          double g = 1.0;
          for (int d = 0; d < dim; ++d) g *= (d == e ? der : val)[qi[d] * np + ji[d]];
          dphi[j * dim + e] = g;
        }
      }
      double J[9] = {0}, inv[9] = {0};
      for (int j = 0; j < nd; ++j)
        for (int a = 0; a < dim; ++a)
          for (int b = 0; b < dim; ++b)
            J[a * dim + b] += coords(a * n_nodes + node[j]) * dphi[j * dim + b];
      const double det = sumfac::inverse<dim>(J, inv);
      // field at the point (coefficient or velocity), from the DoF values
      double f[3] = {1.0, 0.0, 0.0};
      if (!field.empty()) {
        const int comps = kind == solvers::OperatorKind::convection ? dim : 1;
        for (int a = 0; a < comps; ++a) {
          f[a] = 0.0;
          for (int j = 0; j < nd; ++j) {
            int ijk[3] = {0, 0, 0}, r2 = j;
            for (int d = 0; d < dim; ++d) ijk[d] = cell[d] * k + r2 % np, r2 /= np;
            f[a] += field[a * n + lat.dof_index(ijk)] * phi[j];
          }
        }
      }
      std::vector<double> gphys(nd * dim);  // J^-T grad_ref
      for (int j = 0; j < nd; ++j)
        for (int a = 0; a < dim; ++a) {
          double s = 0.0;
          for (int b = 0; b < dim; ++b) s += inv[b * dim + a] * dphi[j * dim + b];
          gphys[j * dim + a] = s;
        }
      for (int i = 0; i < nd; ++i)
        for (int j = 0; j < nd; ++j) {
          double v = 0.0;
          if (kind == solvers::OperatorKind::mass) {
            v = phi[i] * phi[j];
          } else if (kind == solvers::OperatorKind::laplace) {
            for (int a = 0; a < dim; ++a) v += gphys[i * dim + a] * gphys[j * dim + a];
            v *= f[0];
          } else {
            for (int a = 0; a < dim; ++a) v += phi[i] * f[a] * gphys[j * dim + a];
          }
          elem[i * nd + j] += w * det * v;
        }
    }
    for (int i = 0; i < nd; ++i)
      for (int j = 0; j < nd; ++j)
        if (dof[i] >= 0 && dof[j] >= 0) triplets.emplace_back(dof[i], dof[j], elem[i * nd + j]);
  }
  auto cons = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), space.constrained_dofs());
  for (std::size_t i = 0; i < cons.extent(0); ++i) triplets.emplace_back(cons(i), cons(i), 1.0);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  return A;
}

}  // namespace amphora::test
