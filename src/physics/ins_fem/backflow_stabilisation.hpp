#pragma once
// Backflow stabilisation on the open (Neumann, do-nothing) faces of a box: the momentum
// equations gain -beta int_Gamma eps (a . n)_- u . v dGamma, a the advecting velocity,
// (s)_- = min(s, 0), eps the void fraction (1 for clear fluid). Where fluid re-enters through
// an open face, the do-nothing condition lets it bring kinetic energy in unchecked; this term
// removes it and vanishes where the flow leaves (Bazilevs, Gohean, Hughes, Moser & Zhang 2009,
// CMAME 198, eq. 29; Moghadam et al. 2011, Comput. Mech. 48). The face integral uses the
// Gauss-Lobatto nodes (lumped), so the term is diagonal, c_i u_i on each velocity component,
// with the face measure of the undeformed box (on curved cells still dissipative).
#include <array>
#include <stdexcept>
#include <vector>

#include <Kokkos_Core.hpp>

#include "kernels/kokkos_compat.hpp"
#include "kernels/sumfac/quadrature_1d.hpp"
#include "mesh/hex/qk_space.hpp"

namespace amphora::physics::ins_fem {

template <int dim, class ExecSpace>
class BackflowStabilisation {
 public:
  using Space = mesh::hex::QkSpace<dim, ExecSpace>;
  using memory_space = typename ExecSpace::memory_space;
  using Vector = Kokkos::View<double*, memory_space>;

  /// The open faces' unconstrained nodes and their lumped face weights.
  BackflowStabilisation(const Space& space, double beta) : beta_(beta), n_(space.n_dofs()) {
    if (!(beta >= 0.0))
      throw std::invalid_argument("ins_fem: backflow stabilisation beta must be >= 0");
    make_face_nodes(space);
  }

  /// Whether any open face carries the term (beta > 0 and a Neumann face).
  bool active() const { return beta_ > 0.0 && dofs_.extent(0) > 0; }
  /// c_i = beta eps_i sum over the open faces through node i of w_i max(-(a_i . n), 0);
  /// advecting: dim n_dofs (blocked), eps: n_dofs or empty (eps = 1).
  template <class A, class E>
  void update(const ExecSpace& exec, const A& advecting, const E& eps) {
    const auto dofs = dofs_;
    const auto w = weights_;
    const auto c = c_;
    const double beta = beta_;
    const long n = n_;
    const bool scaled = eps.extent(0) > 0;
    Kokkos::parallel_for(
        "amphora::ins_fem::backflow_update",
        kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(dofs.extent(0))),
        KOKKOS_LAMBDA(int m) {
          const long i = dofs(m);
          double s = 0.0;
          for (int f = 0; f < 2 * dim; ++f) {
            const double an = (f % 2 == 1 ? 1.0 : -1.0) * advecting((f / 2) * n + i);
            s += w(m, f) * (an < 0.0 ? -an : 0.0);
          }
          c(m) = beta * (scaled ? eps(i) : 1.0) * s;
        });
  }
  /// y += c u on each velocity component of x (blocked, dim or dim + 1 components).
  template <class X, class Y>
  void apply_add(const ExecSpace& exec, const X& x, const Y& y) const {
    add_coefficients(exec, x, y, true);
  }
  /// diag += c on each velocity component (for point Jacobi).
  template <class Y>
  void add_diagonal(const ExecSpace& exec, const Y& diag) const {
    add_coefficients(exec, diag, diag, false);
  }
  /// sum_i c_i: beta int_Gamma eps max(-(a . n), 0) dGamma (tests).
  double coefficient_sum() const {
    double s = 0.0;
    const auto c = c_;
    Kokkos::parallel_reduce(
        "amphora::ins_fem::backflow_sum",
        kernels::RangePolicy<ExecSpace>(ExecSpace(), 0, static_cast<int>(c.extent(0))),
        KOKKOS_LAMBDA(int m, double& acc) { acc += c(m); }, s);
    return s;
  }

  // (public for CUDA: extended lambdas may not live in private member functions)

  /// y += c x (times_x) or y += c on each velocity component.
  template <class X, class Y>
  void add_coefficients(const ExecSpace& exec, const X& x, const Y& y, bool times_x) const {
    const auto dofs = dofs_;
    const auto c = c_;
    const long n = n_;
    Kokkos::parallel_for(
        "amphora::ins_fem::backflow_apply",
        kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(dofs.extent(0))),
        KOKKOS_LAMBDA(int m) {
          for (int d = 0; d < dim; ++d)
            y(d * n + dofs(m)) += c(m) * (times_x ? x(d * n + dofs(m)) : 1.0);
        });
  }

 private:
  /// Gauss-Lobatto weights of the composite rule along direction e, per DoF layer (a periodic
  /// direction's last node layer is its first).
  static std::vector<double> layer_weights(const Space& space, int e) {
    const auto& l = space.lattice();
    const auto& m = space.mesh();
    const std::vector<double> gw = kernels::sumfac::gauss_lobatto(l.degree + 1).weights;
    const double h = (m.upper[e] - m.lower[e]) / l.cells[e];
    std::vector<double> w(l.dofs[e], 0.0);
    for (int c = 0; c < l.cells[e]; ++c)
      for (int q = 0; q <= l.degree; ++q) w[(c * l.degree + q) % l.dofs[e]] += h * gw[q];
    return w;
  }

  void make_face_nodes(const Space& space) {
    const auto& l = space.lattice();
    bool open = false;
    for (int f = 0; f < 2 * dim; ++f)
      open = open || space.mesh().faces[f] == mesh::hex::FaceCondition::neumann;
    if (!open) return;
    std::vector<char> constrained(n_, 0);
    const auto cons = Kokkos::create_mirror_view(space.constrained_dofs());
    Kokkos::deep_copy(cons, space.constrained_dofs());
    for (std::size_t k = 0; k < cons.extent(0); ++k) constrained[cons(k)] = 1;
    std::vector<std::vector<double>> lw(dim);
    for (int e = 0; e < dim; ++e) lw[e] = layer_weights(space, e);
    std::vector<long> nodes;
    std::vector<std::array<double, 2 * dim>> weights;
    std::vector<int> slot(n_, -1);  // the node's entry
    for (int f = 0; f < 2 * dim; ++f) {
      if (space.mesh().faces[f] != mesh::hex::FaceCondition::neumann) continue;
      const int d = f / 2, layer = f % 2 == 1 ? l.dofs[d] - 1 : 0;
      for (long i = 0; i < n_; ++i) {
        long r = i;
        int idx[3] = {0, 0, 0};
        for (int e = 0; e < dim; ++e) idx[e] = static_cast<int>(r % l.dofs[e]), r /= l.dofs[e];
        if (idx[d] != layer || constrained[i]) continue;
        if (slot[i] < 0) {
          slot[i] = static_cast<int>(nodes.size());
          nodes.push_back(i);
          weights.push_back({});
        }
        double w = 1.0;
        for (int e = 0; e < dim; ++e)
          if (e != d) w *= lw[e][idx[e]];
        weights[slot[i]][f] = w;
      }
    }
    const int nf = static_cast<int>(nodes.size());
    dofs_ = Kokkos::View<long*, memory_space>("amphora::ins_fem::backflow_dofs", nf);
    weights_ = Kokkos::View<double * [2 * dim], memory_space>("amphora::ins_fem::backflow_w", nf);
    c_ = Vector("amphora::ins_fem::backflow_c", nf);
    auto hd = Kokkos::create_mirror_view(dofs_);
    auto hw = Kokkos::create_mirror_view(weights_);
    for (int m = 0; m < nf; ++m) {
      hd(m) = nodes[m];
      for (int f = 0; f < 2 * dim; ++f) hw(m, f) = weights[m][f];
    }
    Kokkos::deep_copy(dofs_, hd);
    Kokkos::deep_copy(weights_, hw);
  }

  double beta_;
  long n_;
  Kokkos::View<long*, memory_space> dofs_;
  Kokkos::View<double * [2 * dim], memory_space> weights_;
  Vector c_;
};

}  // namespace amphora::physics::ins_fem
