#pragma once
// A locking benchmark for incompressible linear tetrahedra (Irving, Schroeder & Fedkiw 2007,
// section 3): a cantilever clamped at x = 0 under its own weight, small strain, the
// incompressibility imposed by a penalty lambda (div u)^2 much larger than mu, per element
// (one constraint per tetrahedron) or per node (the one-ring volumes V_i and their gradient B
// of kernels/solid, as in the volume projection), against Q2 hexahedra with the volumetric
// term reduced-integrated (2 Gauss points per direction), itself checked against Timoshenko
// beam theory. Direct sparse solves (Eigen) of the static problem.
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <cmath>
#include <cstdio>
#include <vector>

#include "kernels/solid/node_volumes.hpp"
#include "kernels/solid/volume_gradient_matrix.hpp"
#include "mesh/hex/qk_space.hpp"
#include "mesh/tet/shape_meshes.hpp"
#include "solvers/reference_assembly.hpp"
#include "test_backend.hpp"

namespace amphora::test::locking {

using test::TestExecSpace;
using Mem = test::TestMemSpace;
using Sparse = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

inline constexpr double kLength = 8.0, kHeight = 1.0;  // the beam [0, L] x [0, h]^2
inline constexpr double kMu = 1.0, kLoad = 1.0;        // shear modulus, weight per volume (-z)

enum class Constraint { element, node };

/// Tip deflection (-u_z at the centre of the face x = L) of Timoshenko's clamped beam under
/// a uniform load q: q L^4 / (8 E I) + q L^2 / (2 kappa G A), incompressible: E = 3 mu,
/// kappa = 5/6 (rectangle).
inline double timoshenko_tip_deflection() {
  const double q = kLoad * kHeight * kHeight, E = 3.0 * kMu, I = std::pow(kHeight, 4) / 12.0;
  return q * std::pow(kLength, 4) / (8.0 * E * I) +
         q * kLength * kLength / (2.0 * (5.0 / 6.0) * kMu * kHeight * kHeight);
}

/// The solution of A u = f on the free DoFs (free[i] < 0: clamped, u_i = 0).
inline Eigen::VectorXd solve_free(const Triplets& all, const Eigen::VectorXd& f,
                                  const std::vector<long>& free) {
  long n_free = 0;
  for (long i : free) n_free = std::max(n_free, i + 1);
  Triplets t;
  for (const auto& e : all)
    if (free[e.row()] >= 0 && free[e.col()] >= 0)
      t.emplace_back(free[e.row()], free[e.col()], e.value());
  Sparse A(n_free, n_free);
  A.setFromTriplets(t.begin(), t.end());
  Eigen::VectorXd b(n_free);
  for (std::size_t i = 0; i < free.size(); ++i)
    if (free[i] >= 0) b[free[i]] = f[i];
  Eigen::SimplicialLDLT<Sparse> solver(A);
  EXPECT_EQ(solver.info(), Eigen::Success) << "factorisation";
  const Eigen::VectorXd x = solver.solve(b);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(f.size());
  for (std::size_t i = 0; i < free.size(); ++i)
    if (free[i] >= 0) u[i] = x[free[i]];
  return u;
}

/// The cubes' split into tetrahedra: the six Kuhn tetrahedra around the main diagonal, or
/// the 24 around the cube's centre and face centres (the split of the curved shapes' meshes).
enum class Split { kuhn6, centred24 };

/// The (8k, k, k) cubes of the beam as hexahedra.
inline std::vector<mesh::tet::Hex> box_hexes(int k) {
  const double h = kHeight / k;
  std::vector<mesh::tet::Hex> hexes;
  for (int i = 0; i < 8 * k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l) {
        mesh::tet::Hex c;
        for (int v = 0; v < 8; ++v)
          c[v] = {(i + (v & 1)) * h, (j + ((v >> 1) & 1)) * h, (l + ((v >> 2) & 1)) * h};
        hexes.push_back(c);
      }
  return hexes;
}

/// The linear-tetrahedron cantilever on (8k, k, k) cubes (k even: a node at the tip's centre).
struct TetCantilever {
  TetCantilever(int k, Split split) {
    mesh = split == Split::kuhn6 ? mesh::tet::box_tet_mesh({8 * k, k, k}, {0.0, 0.0, 0.0},
                                                           {kLength, kHeight, kHeight})
                                 : mesh::tet::tets_from_hexes(box_hexes(k));
    const auto v = mesh::tet::to_views<Mem>(mesh);
    const int nt = mesh.n_tets(), n = mesh.n_nodes();
    Kokkos::View<double*, Mem> vol("V_t", nt), node_vol("V_i", n);
    Kokkos::View<double* [4][3], Mem> grad("g_tc", nt);
    const TestExecSpace exec;
    kernels::solid::tet_volume_gradients(exec, v.tets, v.nodes, vol, grad);
    kernels::solid::node_volumes(exec, v.tets, vol, node_vol);
    auto B = kernels::solid::volume_gradient_graph(v.tets, n);
    kernels::solid::assemble_volume_gradient(exec, grad, B);
    V_t = to_host(vol), V_i = to_host(node_vol);
    g = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), grad);
    row = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), B.row);
    col = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), B.col);
    value = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), B.value);
  }

  static std::vector<double> to_host(const Kokkos::View<double*, Mem>& d) {
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), d);
    return std::vector<double>(h.data(), h.data() + h.extent(0));
  }

  /// 2 mu eps(u) : eps(v) per element, with grad phi_a = g_ta / V_t.
  void add_shear(Triplets& t) const {
    for (int e = 0; e < mesh.n_tets(); ++e)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
          const int na = mesh.tets[e][a], nb = mesh.tets[e][b];
          double dot = 0.0;
          for (int d = 0; d < 3; ++d) dot += g(e, a, d) * g(e, b, d);
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              t.emplace_back(3 * na + i, 3 * nb + j,
                             kMu / V_t[e] * ((i == j ? dot : 0.0) + g(e, a, j) * g(e, b, i)));
        }
  }

  /// lambda (div u)^2 per element: lambda / V_t (g_t . u)^2.
  void add_element_penalty(Triplets& t, double lambda) const {
    for (int e = 0; e < mesh.n_tets(); ++e)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              t.emplace_back(3 * mesh.tets[e][a] + i, 3 * mesh.tets[e][b] + j,
                             lambda / V_t[e] * g(e, a, i) * g(e, b, j));
  }

  /// lambda per node: lambda / V_i ((B u)_i)^2 with B the assembled one-ring volume gradient.
  void add_node_penalty(Triplets& t, double lambda) const {
    for (int n = 0; n < mesh.n_nodes(); ++n)
      for (int p = row(n); p < row(n + 1); ++p)
        for (int q = row(n); q < row(n + 1); ++q)
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              t.emplace_back(3 * col(p) + i, 3 * col(q) + j,
                             lambda / V_i[n] * value(p, i) * value(q, j));
  }

  /// -u_z at the tip's centre under the weight (consistent load V_t / 4 per corner).
  double tip_deflection(Constraint c, double lambda) const {
    Triplets t;
    add_shear(t);
    if (c == Constraint::element)
      add_element_penalty(t, lambda);
    else
      add_node_penalty(t, lambda);
    const int n = mesh.n_nodes();
    Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * n);
    for (int e = 0; e < mesh.n_tets(); ++e)
      for (int a = 0; a < 4; ++a) f[3 * mesh.tets[e][a] + 2] -= kLoad * V_t[e] / 4.0;
    std::vector<long> free(3 * n, -1);
    long m = 0;
    for (int i = 0; i < n; ++i)
      if (mesh.nodes[i][0] > 1e-12)
        for (int d = 0; d < 3; ++d) free[3 * i + d] = m++;
    const Eigen::VectorXd u = solve_free(t, f, free);
    return -u[3 * tip_node() + 2];
  }

  int tip_node() const {
    for (int i = 0; i < mesh.n_nodes(); ++i)
      if (std::abs(mesh.nodes[i][0] - kLength) < 1e-12 &&
          std::abs(mesh.nodes[i][1] - 0.5 * kHeight) < 1e-12 &&
          std::abs(mesh.nodes[i][2] - 0.5 * kHeight) < 1e-12)
        return i;
    ADD_FAILURE() << "no node at the tip's centre";
    return 0;
  }

  /// A host copy of a device View of type T (its layout kept: LayoutLeft on CUDA).
  template <class T>
  using Host = Kokkos::View<T, typename Kokkos::View<T, Mem>::array_layout, Kokkos::HostSpace>;

  mesh::tet::TetMesh mesh;
  std::vector<double> V_t, V_i;
  Host<double* [4][3]> g;
  Host<int*> row, col;
  Host<double* [3]> value;
};

/// The Q2 hexahedron cantilever on (8m, m, m) cells: 2 mu eps : eps by 3 Gauss points per
/// direction, lambda (div u)^2 by 2 (selective reduced integration); -u_z at the tip's centre.
inline double q2_tip_deflection(int m, double lambda) {
  mesh::hex::StructuredHexMesh<3> box;
  box.cells = {8 * m, m, m};
  box.upper = {kLength, kHeight, kHeight};
  box.faces.fill(mesh::hex::FaceCondition::neumann);
  box.faces[0] = mesh::hex::FaceCondition::dirichlet;
  const mesh::hex::QkSpace<3, TestExecSpace> space(box, 2);
  const Sparse A = test::assemble_elasticity_reference<3>(space, 3, 0.0, kMu) +
                   test::assemble_elasticity_reference<3>(space, 2, lambda, 0.0);
  const Sparse M =
      test::assemble_reference<3>(space, solvers::matrix_free::OperatorKind::mass, 3, false, {});
  const long n = space.n_dofs();
  const auto clamped =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), space.constrained_dofs());
  std::vector<bool> is_clamped(n, false);
  for (std::size_t i = 0; i < clamped.extent(0); ++i) is_clamped[clamped(i)] = true;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * n);
  const Eigen::VectorXd load = M * Eigen::VectorXd::Constant(n, kLoad);  // int phi_i
  for (long i = 0; i < n; ++i)
    if (!is_clamped[i]) f[2 * n + i] = -load[i];
  Eigen::SimplicialLDLT<Sparse> solver(A);
  EXPECT_EQ(solver.info(), Eigen::Success) << "Q2 factorisation";
  const Eigen::VectorXd u = solver.solve(f);
  const std::vector<double> p = space.dof_points();
  for (long i = 0; i < n; ++i)
    if (std::abs(p[i] - kLength) < 1e-12 && std::abs(p[n + i] - 0.5 * kHeight) < 1e-12 &&
        std::abs(p[2 * n + i] - 0.5 * kHeight) < 1e-12)
      return -u[2 * n + i];
  ADD_FAILURE() << "no Q2 node at the tip's centre";
  return 0.0;
}

/// The incompressible limit: lambda = 1e6 mu (nu = 0.4999995); ten times more changes the
/// per-node deflection by < 0.5 % (test_solid_locking), so this is the constraint's answer.
inline constexpr double kLambda = 1e6 * kMu;

/// The reference: Q2 on (32, 4, 4) cells at kLambda (computed once).
inline double q2_reference() {
  static const double d = q2_tip_deflection(4, kLambda);
  return d;
}

}  // namespace amphora::test::locking
