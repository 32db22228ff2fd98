// The volume-averaged Navier-Stokes equations (VANS, kernels::sumfac::VansPoint through
// InsSolver): in clear fluid the operator is Oseen's to round-off (and eps times it at a constant
// void fraction); a steady manufactured flow
// with a varying void fraction and drag converges at order k + 1 in models A and B; a void
// fraction falling uniformly in time drives the outflow that continuity asks for.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/ins_fem/flow_checkpoint.hpp"
#include "physics/ins_fem/ins_solver.hpp"
#include "solvers/matrix_free/error_norms.hpp"
#include "test_backend.hpp"

namespace amphora::physics::ins_fem {
// Named, not anonymous: CUDA's extended lambdas may not live in anonymous namespaces.
namespace test_ins_fem_vans {

using solvers::matrix_free::OperatorKind;
using test::TestExecSpace;
template <int dim>
using Operator = solvers::matrix_free::MatrixFreeOperator<dim, TestExecSpace>;
template <int dim>
using Vector = typename Operator<dim>::Vector;

std::vector<double> to_host(const Vector<2>& v) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}
Vector<2> to_device(const std::vector<double>& v) {
  return kernels::to_view<TestExecSpace::memory_space>(v);
}

/// A x for the operator of `kind` with `field` (host vectors).
template <int dim>
std::vector<double> apply(const mesh::hex::QkSpace<dim, TestExecSpace>& space,
                          typename Operator<dim>::Options o, const std::vector<double>& field,
                          const std::vector<double>& x) {
  o.components = dim + 1;
  o.nu = 0.03, o.grad_div = 0.2;
  o.field = to_device(field);
  const Operator<dim> A(space, o);
  const Vector<dim> y("y", x.size());
  A.apply_unconstrained(TestExecSpace(), to_device(x), y);  // (constrained rows: y = x)
  return to_host(y);
}

double relative_difference(const std::vector<double>& a, const std::vector<double>& b,
                           double scale_b = 1.0) {
  double d = 0.0, m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d = std::max(d, std::abs(a[i] - scale_b * b[i]));
    m = std::max(m, std::abs(a[i]));
  }
  return d / m;
}

template <int dim>
void check_clear_fluid(int k) {
  mesh::hex::StructuredHexMesh<dim> m;
  m.cells = {3, 2, dim == 3 ? 2 : 1};
  m.upper = {1.0, 0.8, dim == 3 ? 0.7 : 0.0};
  m.faces[1] = mesh::hex::FaceCondition::neumann;
  m.deformation = mesh::hex::sinusoidal_deformation(dim, 0.05, m.lower, m.upper);
  const mesh::hex::QkSpace<dim, TestExecSpace> space(m, k);
  const long n = space.n_dofs();
  std::mt19937 gen(7 + k);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  std::vector<double> b(dim * n), x((dim + 1) * n);
  for (auto& v : b) v = r(gen);
  for (auto& v : x) v = r(gen);
  auto vans_field = [&](double eps, double beta) {
    std::vector<double> f(b);
    f.resize((dim + 2) * n, eps);
    for (long i = 0; i < n; ++i) f[(dim + 1) * n + i] = beta;
    return f;
  };
  for (const bool history : {false, true}) {
    if (history)  // Oseen's history has no continuity source; VANS's is h_p, here 0
      std::fill(x.begin() + dim * n, x.end(), 0.0);
    typename Operator<dim>::Options o;
    o.alpha = 2.0, o.dt_inverse = 1.0, o.history = history;
    o.kind = OperatorKind::oseen;
    const std::vector<double> oseen = apply<dim>(space, o, b, x);
    o.kind = OperatorKind::vans;
    for (const bool model_b : {false, true}) {
      o.model_b = model_b;
      EXPECT_LT(relative_difference(oseen, apply<dim>(space, o, vans_field(1.0, 0.0), x)), 1e-13)
          << "dim " << dim << " k " << k << " history " << history << " model B " << model_b;
    }
    o.model_b = false;  // model A at eps = 0.4: every term (continuity too) times eps
    EXPECT_LT(relative_difference(apply<dim>(space, o, vans_field(0.4, 0.0), x), oseen, 0.4), 1e-13)
        << "dim " << dim << " k " << k << " history " << history;
  }
}

TEST(InsFemVans, ClearFluidIsOseenAndConstantVoidFractionScalesIt) {
  for (int k = 1; k <= 3; ++k) {
    check_clear_fluid<2>(k);
    check_clear_fluid<3>(k);
  }
}

/// An operator rebuilt in a recycled operator's arrays (as the flow rebuilds its step
/// operators) gives the bits of one set up afresh with the same options.
TEST(InsFemVans, AnOperatorInRecycledArraysGivesTheSameBits) {
  constexpr int dim = 3;
  mesh::hex::StructuredHexMesh<dim> m;
  m.cells = {3, 2, 2};
  m.upper = {1.0, 0.8, 0.7};
  m.deformation = mesh::hex::sinusoidal_deformation(dim, 0.05, m.lower, m.upper);
  const mesh::hex::QkSpace<dim, TestExecSpace> space(m, 2);
  const long n = space.n_dofs();
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> r(0.3, 1.0);
  std::vector<double> f1((dim + 2) * n), f2((dim + 2) * n), x((dim + 1) * n);
  for (auto* v : {&f1, &f2, &x})
    for (auto& e : *v) e = r(gen);
  typename Operator<dim>::Options o;
  o.kind = OperatorKind::vans;
  o.components = dim + 1;
  o.nu = 0.03, o.grad_div = 0.2, o.alpha = 2.0, o.dt_inverse = 1.0;
  o.field = to_device(f1);
  Operator<dim> old(space, o);
  o.alpha = 3.0, o.dt_inverse = 1.5, o.model_b = true, o.history = true;
  o.field = to_device(f2);
  const Operator<dim> fresh(space, o), renewed(space, o, std::move(old));
  const Vector<dim> y1("y1", x.size()), y2("y2", x.size());
  fresh.apply_unconstrained(TestExecSpace(), to_device(x), y1);
  renewed.apply_unconstrained(TestExecSpace(), to_device(x), y2);
  EXPECT_EQ(to_host(y1), to_host(y2));
}

/// A steady VANS flow on the periodic unit square: eps = 0.6 + 0.25 cos 2 pi x sin 2 pi y,
/// u = curl psi / eps with psi = sin 2 pi x sin 2 pi y / (2 pi) (so div(eps u) = 0),
/// p = cos 2 pi x cos 2 pi y / 2, drag beta = 2 (1 + sin 2 pi x sin 2 pi y / 2).
struct ManufacturedVans {
  static constexpr double k = 2.0 * kernels::math::pi;
  int component = 0;

  KOKKOS_INLINE_FUNCTION static double eps(const double* x) {
    return 0.6 + 0.25 * kernels::math::cos(k * x[0]) * kernels::math::sin(k * x[1]);
  }
  KOKKOS_INLINE_FUNCTION static double beta(const double* x) {
    return 2.0 + kernels::math::sin(k * x[0]) * kernels::math::sin(k * x[1]);
  }
  KOKKOS_INLINE_FUNCTION double value(const double* x) const {
    using kernels::math::cos;
    using kernels::math::sin;
    const double sx = sin(k * x[0]), cx = cos(k * x[0]), sy = sin(k * x[1]), cy = cos(k * x[1]);
    if (component == 0) return sx * cy / eps(x);
    if (component == 1) return -cx * sy / eps(x);
    return 0.5 * cx * cy;
  }
  KOKKOS_INLINE_FUNCTION void gradient(const double* x, double* d) const {
    using kernels::math::cos;
    using kernels::math::sin;
    const double sx = sin(k * x[0]), cx = cos(k * x[0]), sy = sin(k * x[1]), cy = cos(k * x[1]);
    const double e = eps(x), ex = -0.25 * k * sx * sy, ey = 0.25 * k * cx * cy;
    if (component == 2) {
      d[0] = -0.5 * k * sx * cy, d[1] = -0.5 * k * cx * sy;
      return;
    }
    // u = q / eps: grad u = (grad q eps - q grad eps) / eps^2
    const double q = component == 0 ? sx * cy : -cx * sy;
    const double qx = component == 0 ? k * cx * cy : k * sx * sy;
    const double qy = component == 0 ? -k * sx * sy : -k * cx * cy;
    d[0] = (qx * e - q * ex) / (e * e), d[1] = (qy * e - q * ey) / (e * e);
  }

  /// The force F (per unit mass, times eps in the equations) that makes this flow steady:
  /// eps F = eps u.grad u + s grad p - div(eps nu grad u) + beta u, s = eps (A) or 1 (B); the
  /// divergence by fourth-order central differences of the exact eps grad u (h = 1e-3: 1e-9).
  static double force(const double* x, int i, double nu, bool model_b) {
    ManufacturedVans f{i};
    double g[2], gp[2];
    f.gradient(x, g);
    ManufacturedVans{2}.gradient(x, gp);
    double viscous = 0.0;
    const double h = 1e-3, w[4] = {1.0, -8.0, 8.0, -1.0}, o[4] = {-2.0, -1.0, 1.0, 2.0};
    for (int a = 0; a < 2; ++a)
      for (int j = 0; j < 4; ++j) {
        double y[2] = {x[0], x[1]}, gy[2];
        y[a] += o[j] * h;
        f.gradient(y, gy);
        viscous += w[j] * eps(y) * gy[a] / (12.0 * h);
      }
    const double e = eps(x);
    const double conv = ManufacturedVans{0}.value(x) * g[0] + ManufacturedVans{1}.value(x) * g[1];
    return (e * conv + (model_b ? 1.0 : e) * gp[i] - nu * viscous + beta(x) * f.value(x)) / e;
  }
};

struct VansErrors {
  double u = 0.0, p = 0.0;
};

VansErrors manufactured(int k, int cells, bool model_b) {
  using Solver = InsSolver<2, TestExecSpace>;
  mesh::hex::StructuredHexMesh<2> m;
  m.cells = {cells, cells, 1};
  for (int f = 0; f < 4; ++f) m.faces[f] = mesh::hex::FaceCondition::periodic;
  InsOptions o;
  o.model = model_b ? FlowModel::vans_b : FlowModel::vans_a;
  o.nu = 0.05;
  o.grad_div = 0.1;
  o.tolerance = 1e-11;
  Solver s(m, k, o);
  auto nodal = [&](auto f, int components) {
    return s.space().interpolate([&](const mesh::hex::Point3& x, int c) { return f(x.data(), c); },
                                 components);
  };
  s.set_void_fraction(
      to_device(nodal([](const double* x, int) { return ManufacturedVans::eps(x); }, 1)));
  s.set_drag(to_device(nodal([](const double* x, int) { return ManufacturedVans::beta(x); }, 1)));
  s.set_force(nodal(
      [&](const double* x, int c) { return ManufacturedVans::force(x, c, o.nu, model_b); }, 2));
  s.set_state(nodal([](const double* x, int c) { return ManufacturedVans{c}.value(x); }, 3));
  int picard = 0;
  const InsStepReport r = s.solve_steady(1e-10, 40, &picard);
  EXPECT_TRUE(r.converged) << "k " << k << " cells " << cells << ": " << picard << " Picard, "
                           << r.linear_iterations << " GMRES";
  const TestExecSpace exec;
  const long n = s.n_dofs();
  VansErrors e;
  for (int c = 0; c < 2; ++c) {
    const Vector<2> uc = Kokkos::subview(s.state(), Kokkos::make_pair(c * n, (c + 1) * n));
    const double l2 =
        solvers::matrix_free::error_norms(exec, s.space(), uc, ManufacturedVans{c}).l2;
    e.u += l2 * l2;
  }
  e.u = std::sqrt(e.u);
  e.p = solvers::matrix_free::error_norms(exec, s.space(), s.pressure(), ManufacturedVans{2})
            .l2_mean_free();
  return e;
}

TEST(InsFemVans, ManufacturedFlowWithVaryingVoidFractionConvergesAtOrderKPlusOne) {
  for (const bool model_b : {false, true})
    for (int k = 1; k <= 2; ++k) {
      const int n0 = k == 1 ? 16 : 8, n1 = 2 * n0;
      const VansErrors a = manufactured(k, n0, model_b), b = manufactured(k, n1, model_b);
      const double ou = std::log2(a.u / b.u), op = std::log2(a.p / b.p);
      std::printf(
          "model %c k %d, %d -> %d cells: u %.3e -> %.3e (order %.2f), p %.3e -> %.3e "
          "(%.2f)\n",
          model_b ? 'B' : 'A', k, n0, n1, a.u, b.u, ou, a.p, b.p, op);
      EXPECT_NEAR(ou, k + 1, 0.25) << "model B " << model_b << " k " << k;
      EXPECT_GT(op, k - 0.2) << "model B " << model_b << " k " << k;
    }
}

/// Outflow u = a x (exact) with pressure p.
struct Drain {
  double a = 0.5, nu = 0.02, eps = 1.0;
  bool model_b = false;
  int component = 0;
  /// p = p(1) + s a^2 (1 - x^2) / 2, s = 1 (A) or eps (B); the outflow's natural condition
  /// p(1) = nu a (A) or eps nu a (B).
  KOKKOS_INLINE_FUNCTION double value(const double* x) const {
    const double s = model_b ? eps : 1.0;
    if (component == 0) return a * x[0];
    if (component == 1) return 0.0;
    return s * nu * a + s * a * a * (1.0 - x[0] * x[0]) / 2.0;
  }
  KOKKOS_INLINE_FUNCTION void gradient(const double* x, double* d) const {
    d[0] = component == 0 ? a : component == 2 ? -(model_b ? eps : 1.0) * a * a * x[0] : 0.0;
    d[1] = 0.0;
  }
};

/// The L2 errors of velocity and pressure against `exact` (a Drain) in the unit box, closed at
/// x = 0, open at x = 1, periodic in y, with eps^i = eps_at(i) after step i of dt (uniform in
/// space): continuity eps div u = -d eps / dt makes u = -(d eps / dt) x / eps.
template <class EpsAt, class Exact>
VansErrors drain_errors(bool model_b, VoidFractionRate rate, double dt, int steps, EpsAt eps_at,
                        Exact exact) {
  mesh::hex::StructuredHexMesh<2> m;
  m.cells = {4, 2, 1};
  m.upper = {1.0, 0.5, 0.0};
  m.faces[1] = mesh::hex::FaceCondition::neumann;
  m.faces[2] = m.faces[3] = mesh::hex::FaceCondition::periodic;
  InsOptions o;
  o.model = model_b ? FlowModel::vans_b : FlowModel::vans_a;
  o.void_fraction_rate = rate;
  o.nu = 0.02;
  o.grad_div = 0.1;
  o.tolerance = 1e-12;
  InsSolver<2, TestExecSpace> s(m, 2, o);
  const Vector<2> eps("eps", s.n_dofs());
  for (int i = 0; i <= steps; ++i) {
    Kokkos::deep_copy(eps, eps_at(i));
    s.set_void_fraction(eps);
    if (i > 0) {
      EXPECT_TRUE(s.step(dt).converged) << "step " << i;
    }
  }
  const long n = s.n_dofs();
  VansErrors e;
  for (int c = 0; c < 2; ++c) {
    exact.component = c;
    const Vector<2> uc = Kokkos::subview(s.state(), Kokkos::make_pair(c * n, (c + 1) * n));
    e.u += std::pow(solvers::matrix_free::error_norms(TestExecSpace(), s.space(), uc, exact).l2, 2);
  }
  e.u = std::sqrt(e.u);
  exact.component = 2;
  e.p = solvers::matrix_free::error_norms(TestExecSpace(), s.space(), s.pressure(), exact).l2;
  return e;
}

/// eps(t) = 0.8 exp(-a t) everywhere (particles filling the box uniformly): continuity
/// eps div u = -d eps / dt = a eps gives u = a x, and the momentum balance the pressure (Drain).
/// Q2 holds both exactly, so what remains is the rate's error in d eps / dt, O((a dt)^2), for
/// the BDF2 and the filtered rate alike.
TEST(InsFemVans, FallingVoidFractionDrivesTheOutflowContinuityAsks) {
  for (const VoidFractionRate rate : {VoidFractionRate::bdf, VoidFractionRate::filtered}) {
    for (const bool model_b : {false, true}) {
      Drain exact;
      exact.model_b = model_b, exact.nu = 0.02;
      double error[2];
      for (int r = 0; r < 2; ++r) {
        const double dt = 0.02 / (1 << r);
        const int steps = 20 << r;
        const auto eps_at = [&](int i) { return 0.8 * std::exp(-exact.a * i * dt); };
        exact.eps = eps_at(steps);
        const VansErrors e = drain_errors(model_b, rate, dt, steps, eps_at, exact);
        error[r] = e.u;
        if (r == 0) {
          EXPECT_LT(e.p, 1e-3 * exact.a * exact.a) << "model B " << model_b;
        }
      }
      const double u_norm = exact.a / std::sqrt(3.0 * 2.0);  // |a x| over [0, 1] x [0, 0.5]
      std::printf("%s, model %c: u error %.3e, %.3e at dt / 2 (of %.3e)\n",
                  rate == VoidFractionRate::bdf ? "bdf" : "filtered", model_b ? 'B' : 'A', error[0],
                  error[1], u_norm);
      EXPECT_LT(error[0], 1e-3 * u_norm) << "model B " << model_b;
      EXPECT_GT(error[0] / error[1], 3.5) << "second order; model B " << model_b;
      EXPECT_LT(error[0] / error[1], 4.5) << "second order; model B " << model_b;
    }
  }
}

/// eps alternating by 1e-3 from step to step (a settled bed's period-two mode, docs/cfd_dem.md):
/// BDF2 turns it into a rate of 4 x 1e-3 / dt, alternating, and an outflow; the filtered rate
/// sees none once it has four levels.
TEST(InsFemVans, FilteredVoidFractionRateIgnoresAPeriodTwoAlternation) {
  const double dt = 0.02, delta = 1e-3, eps0 = 0.8;
  const auto eps_at = [&](int i) { return eps0 + (i % 2 ? delta : -delta); };
  const double bdf_rate = 4.0 * delta / dt;  // (3 + 4 + 1) delta / (2 dt) in size
  const double u_norm = bdf_rate / eps0 / std::sqrt(3.0 * 2.0);  // |rate x / eps|
  Drain none;                                                    // u = 0: a = 0
  none.a = 0.0, none.eps = eps0;
  for (const VoidFractionRate rate : {VoidFractionRate::bdf, VoidFractionRate::filtered}) {
    const double u = drain_errors(false, rate, dt, 9, eps_at, none).u;
    std::printf("%s: |u| %.3e (BDF2's alternation: %.3e)\n",
                rate == VoidFractionRate::bdf ? "bdf" : "filtered", u, u_norm);
    if (rate == VoidFractionRate::bdf) {
      EXPECT_NEAR(u, u_norm, 0.05 * u_norm);
    } else {
      EXPECT_LT(u, 1e-8 * u_norm);
    }
  }
}

/// A checkpoint's flow block restores the solver and returns the owner's history entries; a
/// block that does not fit is refused with what does not fit (a VANS block without the void
/// fraction's history, as written before the flow kept it; a history too short; no block).
TEST(InsFemVans, AFlowBlockThatDoesNotFitIsRefusedSayingWhy) {
  mesh::hex::StructuredHexMesh<3> m;
  m.cells = {2, 2, 2};
  InsOptions fo;
  fo.model = FlowModel::vans_a;
  fo.nu = 0.1;
  fo.transient_tau = true;
  InsSolver<3, TestExecSpace> flow(m, 1, fo);
  const StateBlock b = flow_state_block(flow, {7.0});
  EXPECT_EQ(restore_flow_block<3>(flow, b, "test", 1), std::vector<double>{7.0});
  const auto refusal = [&](const StateBlock& block) {
    try {
      restore_flow_block<3>(flow, block, "test", 1);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("(restored)");
  };
  const auto without = [&](const std::string& key) {
    StateBlock c = b;
    c.arrays.erase(std::remove_if(c.arrays.begin(), c.arrays.end(),
                                  [&](const auto& a) { return a.first == key; }),
                   c.arrays.end());
    return c;
  };
  const std::string eps =
      "0 void fraction history entries, the scene has " + std::to_string(3 * flow.n_dofs() + 1);
  EXPECT_NE(refusal(without("eps")).find(eps), std::string::npos) << refusal(without("eps"));
  StateBlock short_history = b;
  for (auto& [key, v] : short_history.arrays)
    if (key == "history") v.resize(2);
  EXPECT_NE(refusal(short_history).find("2 history entries, this module needs 3"),
            std::string::npos)
      << refusal(short_history);
  EXPECT_NE(refusal(StateBlock{"flow", {}}).find("test: the checkpoint has no flow block"),
            std::string::npos);
}

}  // namespace test_ins_fem_vans
}  // namespace amphora::physics::ins_fem
