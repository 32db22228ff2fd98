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
#include "solvers/matrix_free/matrix_free_operator.hpp"

namespace amphora::test {

/// The matrix of the bilinear form entry(ci, i, cj, j, phi, gphys, f, det, lap) (components
/// ci, cj of basis functions i, j; values phi, physical gradients gphys[i * dim + a], field
/// values f, det J and the physical Laplacians lap (exact on affine cells) at the point), times w
/// det J, summed over points; comps blocked components, of which the first `constrained_comps` (-1:
/// all) have the Dirichlet rows.
template <int dim, class Space, class Entry>
Eigen::SparseMatrix<double> assemble_form(const Space& space, int n_q, bool gauss_lobatto,
                                          const std::vector<double>& field, int field_comps,
                                          int comps, const Entry& entry,
                                          int constrained_comps = -1) {
  if (constrained_comps < 0) constrained_comps = comps;
  const auto& lat = space.lattice();
  const int k = lat.degree, np = k + 1;
  const std::vector<double> nodes = kernels::sumfac::gauss_lobatto(np).points;
  const kernels::sumfac::Quadrature1D q =
      gauss_lobatto ? kernels::sumfac::gauss_lobatto(n_q) : kernels::sumfac::gauss(n_q);
  const std::vector<double> val = kernels::sumfac::lagrange_values(nodes, q.points);
  const std::vector<double> der = kernels::sumfac::lagrange_derivatives(nodes, q.points);
  // second derivatives: the derivative's nodal values differentiated again
  const std::vector<double> dn = kernels::sumfac::lagrange_derivatives(nodes, nodes);
  std::vector<double> der2(q.points.size() * np, 0.0);
  for (std::size_t p = 0; p < q.points.size(); ++p)
    for (int j = 0; j < np; ++j)
      for (int m = 0; m < np; ++m) der2[p * np + j] += der[p * np + m] * dn[m * np + j];
  auto coords = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), space.coordinates());
  const long n_nodes = lat.n_nodes(), n = lat.n_dofs();
  int nd = 1, nqt = 1;
  for (int d = 0; d < dim; ++d) nd *= np, nqt *= n_q;
  std::vector<Eigen::Triplet<double>> triplets;
  int cell[3] = {0, 0, 0};
  const int n_cells = static_cast<int>(space.mesh().n_cells());
  std::vector<long> dof(nd), free_dof(nd), node(nd);
  const int m = comps * nd;
  std::vector<double> phi(nd), dphi(nd * dim), elem(m * m);
  for (int c = 0; c < n_cells; ++c) {
    int rest = c;
    for (int d = 0; d < dim; ++d) cell[d] = rest % lat.cells[d], rest /= lat.cells[d];
    for (int j = 0; j < nd; ++j) {
      int ijk[3] = {0, 0, 0}, r = j;
      for (int d = 0; d < dim; ++d) ijk[d] = cell[d] * k + r % np, r /= np;
      free_dof[j] = lat.dof_index(ijk);
      dof[j] = lat.constrained(ijk) ? -1 : free_dof[j];
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
      const double det = kernels::sumfac::inverse<dim>(J, inv);
      // field at the point (coefficient or velocity), from the DoF values
      double f[3] = {1.0, 0.0, 0.0};
      if (!field.empty()) {
        for (int a = 0; a < field_comps; ++a) {
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
      // physical Laplacians J^-T H J^-1 (exact on affine cells: no derivative of J^-1)
      std::vector<double> lap(nd, 0.0);
      for (int j = 0; j < nd; ++j) {
        int ji[3] = {0, 0, 0}, rj = j;
        for (int d = 0; d < dim; ++d) ji[d] = rj % np, rj /= np;
        for (int b = 0; b < dim; ++b)
          for (int c2 = 0; c2 < dim; ++c2) {
            double h = 1.0;
            for (int d = 0; d < dim; ++d) {
              const int order = (d == b) + (d == c2);
              const std::vector<double>& t = order == 2 ? der2 : order == 1 ? der : val;
              h *= t[qi[d] * np + ji[d]];
            }
            double metric = 0.0;
            for (int a = 0; a < dim; ++a) metric += inv[b * dim + a] * inv[c2 * dim + a];
            lap[j] += metric * h;
          }
      }
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j)
          elem[i * m + j] +=
              w * det *
              entry(i / nd, i % nd, j / nd, j % nd, phi.data(), gphys.data(), f, det, lap.data());
    }
    auto row = [&](int i) { return (i / nd < constrained_comps ? dof : free_dof)[i % nd]; };
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j)
        if (row(i) >= 0 && row(j) >= 0)
          triplets.emplace_back((i / nd) * n + row(i), (j / nd) * n + row(j), elem[i * m + j]);
  }
  auto cons = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), space.constrained_dofs());
  for (int c = 0; c < constrained_comps; ++c)
    for (std::size_t i = 0; i < cons.extent(0); ++i)
      triplets.emplace_back(c * n + cons(i), c * n + cons(i), 1.0);
  Eigen::SparseMatrix<double> A(comps * n, comps * n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  return A;
}

/// Mass, Laplace (times the field a(x) if given) or convection (by the field b(x)).
template <int dim, class Space>
Eigen::SparseMatrix<double> assemble_reference(const Space& space,
                                               solvers::matrix_free::OperatorKind kind, int n_q,
                                               bool gauss_lobatto,
                                               const std::vector<double>& field) {
  const int field_comps = kind == solvers::matrix_free::OperatorKind::convection ? dim : 1;
  return assemble_form<dim>(space, n_q, gauss_lobatto, field, field_comps, 1,
                            [&](int, int i, int, int j, const double* phi, const double* g,
                                const double* f, double, const double*) {
                              double v = 0.0;
                              if (kind == solvers::matrix_free::OperatorKind::mass) {
                                v = phi[i] * phi[j];
                              } else if (kind == solvers::matrix_free::OperatorKind::laplace) {
                                for (int a = 0; a < dim; ++a) v += g[i * dim + a] * g[j * dim + a];
                                v *= f[0];
                              } else {
                                for (int a = 0; a < dim; ++a) v += phi[i] * f[a] * g[j * dim + a];
                              }
                              return v;
                            });
}

/// Isotropic linear elasticity: a(u, v) = int lambda div u div v + 2 mu eps(u) : eps(v), the
/// row of test function i of component ci against trial function j of component cj.
template <int dim, class Space>
Eigen::SparseMatrix<double> assemble_elasticity_reference(const Space& space, int n_q,
                                                          double lambda, double mu) {
  return assemble_form<dim>(
      space, n_q, false, {}, 0, dim,
      [&](int ci, int i, int cj, int j, const double*, const double* g, const double*, double,
          const double*) {
        // eps(phi_j e_cj) : eps(phi_i e_ci) = (d_ci dphi_j...) from the symmetric gradients
        double eps_u[dim][dim] = {}, eps_v[dim][dim] = {};
        for (int a = 0; a < dim; ++a) {
          eps_u[cj][a] += 0.5 * g[j * dim + a], eps_u[a][cj] += 0.5 * g[j * dim + a];
          eps_v[ci][a] += 0.5 * g[i * dim + a], eps_v[a][ci] += 0.5 * g[i * dim + a];
        }
        double v = lambda * g[j * dim + cj] * g[i * dim + ci];
        for (int a = 0; a < dim; ++a)
          for (int b = 0; b < dim; ++b) v += 2.0 * mu * eps_u[a][b] * eps_v[a][b];
        return v;
      });
}

/// The stabilised Oseen operator of kernels::sumfac::OseenPoint, written out term by term for
/// test function (ci, i) and trial function (cj, j), components 0 .. dim-1 velocity, dim
/// pressure; `field` the advecting velocity b (dim blocked). The pressure has no Dirichlet rows.
template <int dim, class Space, class Options>
Eigen::SparseMatrix<double> assemble_oseen_reference(const Space& space, int n_q,
                                                     const std::vector<double>& field,
                                                     const Options& o) {
  const int k = space.degree();
  return assemble_form<dim>(
      space, n_q, false, field, dim, dim + 1,
      [&](int ci, int i, int cj, int j, const double* phi, const double* g, const double* b,
          double det, const double* lap) {
        const double h2 = std::pow(std::abs(det), 2.0 / dim) / (k * k);
        double bb = 0.0, b_gi = 0.0, b_gj = 0.0;
        for (int a = 0; a < dim; ++a)
          bb += b[a] * b[a], b_gi += b[a] * g[i * dim + a], b_gj += b[a] * g[j * dim + a];
        const double visc = 12.0 * o.nu / h2;
        const double tau =
            1.0 / std::sqrt(4.0 * o.dt_inverse * o.dt_inverse + 4.0 * bb / h2 + visc * visc);
        const double alpha = o.history ? 1.0 : o.alpha;
        // strong residual of the trial function: alpha u + b.grad u + grad p (history: u)
        double r[3] = {0.0, 0.0, 0.0};
        if (cj < dim)
          r[cj] = alpha * phi[j] +
                  (o.history ? 0.0 : b_gj - (o.viscous_residual ? o.nu * lap[j] : 0.0));
        else if (!o.history)
          for (int a = 0; a < dim; ++a) r[a] = g[j * dim + a];
        // the test function's stabilisation weight: b.grad v or grad q
        double stab = 0.0;
        if (ci < dim)
          stab = b_gi * r[ci];
        else
          for (int a = 0; a < dim; ++a) stab += g[i * dim + a] * r[a];
        double v = tau * stab;
        if (ci < dim && cj < dim && ci == cj) v += alpha * phi[i] * phi[j];
        if (o.history) return v;
        if (ci < dim && cj < dim) {
          if (ci == cj) {
            v += phi[i] * b_gj;
            for (int a = 0; a < dim; ++a) v += o.nu * g[i * dim + a] * g[j * dim + a];
          }
          v += o.grad_div * g[i * dim + ci] * g[j * dim + cj];
        } else if (ci < dim) {
          v -= g[i * dim + ci] * phi[j];  // -(div v, p)
        } else if (cj < dim) {
          v += phi[i] * g[j * dim + cj];  // (q, div u)
        }
        return v;
      },
      dim);  // Dirichlet rows for the velocity only: the pressure is free on every face
}

}  // namespace amphora::test
