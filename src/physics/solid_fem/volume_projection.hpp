#pragma once
// Volume preservation per node for the tetrahedral solid (Irving, Schroeder & Fedkiw,
// SIGGRAPH 2007): one pressure per node on its one-ring (kernels/solid/node_volumes). After
// the elastic step, a position correction x += W B^T q with (B W B^T) q = V_0 - V(x), in
// Newton iterations, and a velocity projection v += W B^T p with (B W B^T) p = r - B v, r = 0
// (or (V_0 - V)/tau when the error is instead recovered over a time tau, without the position
// correction). B is assembled on the node graph each time x changes
// (kernels/solid/volume_gradient_matrix.hpp); B W B^T is symmetric semi-definite: Jacobi-
// preconditioned conjugate residuals solve it. W is the
// inverse lumped mass, zero at pinned nodes, with the normal of a node that touches a plane
// projected out: frictionless contacts are linear constraints inside the solve. Only scalars
// (dot products, maxima) come back to the host.
#include <algorithm>
#include <cmath>
#include <string>

#include "kernels/blas1.hpp"
#include "kernels/solid/node_update.hpp"
#include "kernels/solid/node_volumes.hpp"
#include "kernels/solid/volume_gradient_matrix.hpp"

namespace amphora::physics::solid_fem {

struct VolumeOptions {
  double tolerance = 1e-8;     ///< per-node |V_i - V_0i| / V_0i after the position correction
  double cr_tolerance = 1e-3;  ///< each linear residual relative to its right-hand side
  int max_cr = 2000;           ///< conjugate-residual iterations per solve
  int max_newton = 10;         ///< position corrections per step
  double recovery_time = 0.0;  ///< tau [s]; 0: the volume is corrected every step
  double contact_gap = 0.0;    ///< a node this close to a plane touches it [m]
};

struct VolumeReport {
  int corrections = 0, cr_iterations = 0;
  double error_before = 0.0;  ///< the largest per-node relative volume error before the step's
  double error = 0.0;         ///< ... and after its position correction
  double rate = 0.0;  ///< the largest |(B v)_i - r_i| / V_0i after the velocity projection [1/s]
  bool converged = false;
};

template <class ExecSpace>
class VolumeProjection {
 public:
  using Mem = typename ExecSpace::memory_space;
  using Nodes = Kokkos::View<double* [3], Mem>;
  using Scalars = Kokkos::View<double*, Mem>;
  using Tets = Kokkos::View<int* [4], Mem>;

  /// The rest one-ring volumes V_0 from the rest positions X.
  VolumeProjection(const Tets& tets, const Nodes& X, const VolumeOptions& o,
                   const ExecSpace& exec = ExecSpace())
      : o_(o), exec_(exec), tets_(tets) {
    const int n = static_cast<int>(X.extent(0)), m = static_cast<int>(tets.extent(0));
    auto scalars = [n](const std::string& name) { return Scalars(name, n); };
    V0_ = scalars("amphora::solid::volume::V0"), V_ = scalars("amphora::solid::volume::V");
    rhs_ = scalars("amphora::solid::volume::rhs"),
    target_ = scalars("amphora::solid::volume::target");
    q_ = scalars("amphora::solid::volume::q");
    r_ = scalars("amphora::solid::volume::r"), p_ = scalars("amphora::solid::volume::p");
    Ar_ = scalars("amphora::solid::volume::Ar"), Ap_ = scalars("amphora::solid::volume::Ap");
    w_ = scalars("amphora::solid::volume::w"), diag_ = scalars("amphora::solid::volume::diag");
    z_ = scalars("amphora::solid::volume::z"), y_ = scalars("amphora::solid::volume::y");
    q_position_ = scalars("amphora::solid::volume::q_position");
    q_velocity_ = scalars("amphora::solid::volume::q_velocity");
    normal_ = Nodes("amphora::solid::volume::normal", n);
    u_ = Nodes("amphora::solid::volume::u", n);
    vol_ = Scalars("amphora::solid::volume::tet_volume", m);
    grad_ = Kokkos::View<double* [4][3], Mem>("amphora::solid::volume::grad", m);
    B_ = kernels::solid::volume_gradient_graph(tets_, n);
    kernels::solid::tet_volume_gradients(exec_, tets_, X, vol_, grad_);
    kernels::solid::node_volumes(exec_, tets_, vol_, V0_);
    volume_norm_ = std::sqrt(kernels::blas1::dot(exec_, V0_, V0_));
    length_ = std::cbrt(kernels::blas1::sum(exec_, V0_) / n);
  }

  /// Newton iterations x += W B^T q, (B W B^T) q = V_0 - V(x), until the per-node relative
  /// error is below the tolerance (none with recovery_time > 0: the velocities recover it).
  VolumeReport correct_positions(const Nodes& x) {
    VolumeReport rep;
    update_volumes(x);
    rep.error_before = rep.error = relative_error();
    cr_converged_ = true;
    bool solved = true;
    while (o_.recovery_time == 0.0 && rep.corrections < o_.max_newton && rep.error > o_.tolerance) {
      volume_difference(1.0, rhs_);
      // The last step's first correction starts the first; the later ones start from zero.
      if (rep.corrections > 0) Kokkos::deep_copy(exec_, q_position_, 0.0);
      rep.cr_iterations += solve(1e-13 * volume_norm_, q_position_);
      solved = solved && cr_converged_;
      correct(x);
      update_volumes(x);
      rep.error = relative_error();
      ++rep.corrections;
    }
    rep.converged = solved && (o_.recovery_time > 0.0 || rep.error <= o_.tolerance);
    return rep;
  }

  /// v += W B^T p with (B W B^T) p = r - B v: the one-ring volumes' rate B v at x becomes
  /// r = 0, or (V_0 - V) / tau with a recovery time.
  void project_velocities(const Nodes& x, const Nodes& v, VolumeReport& rep) {
    using kernels::blas1::axpby;
    update_volumes(x);
    volume_difference(o_.recovery_time > 0.0 ? 1.0 / o_.recovery_time : 0.0, target_);
    kernels::solid::volume_gradient_matrix_apply(exec_, B_, v, Ar_);
    Kokkos::deep_copy(exec_, rhs_, target_);
    axpby(exec_, -1.0, Ar_, 1.0, rhs_);  // r - B v
    rep.cr_iterations += solve(1e-13 * volume_norm_ * max_speed(v) / length_, q_velocity_);
    rep.converged = rep.converged && cr_converged_;
    correct(v);
    kernels::solid::volume_gradient_matrix_apply(exec_, B_, v, Ar_);
    axpby(exec_, -1.0, target_, 1.0, Ar_);
    rep.rate = relative_max(Ar_);
  }

  const Scalars& rest_volumes() const { return V0_; }
  /// The one-ring volumes at the last positions update_volumes() saw.
  const Scalars& volumes() const { return V_; }

  // The pieces (public: CUDA forbids extended lambdas in private members).

  /// W for the coming corrections: 1/m_i, zero at pinned nodes and at nodes on two planes
  /// that are not parallel; the unit normal of the plane a node touches (zero: none). With
  /// dt > 0 (before a drift of dt with velocities v), a node touches a plane it would pass,
  /// and its normal velocity is set to land on it: the drift's contacts become constraints
  /// of the velocity projection. With dt = 0, a node touches a plane it lies on.
  void set_weights(const Scalars& mass, const Kokkos::View<char*, Mem>& pinned,
                   const kernels::solid::BoundingPlanes& pl, const Nodes& x, const Nodes& v,
                   double dt) {
    const auto w = w_;
    const auto nrm = normal_;
    const double tol = o_.contact_gap;
    Kokkos::parallel_for(
        "amphora::solid::volume::weights", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i) {
          double nn[3] = {0.0, 0.0, 0.0};
          int touching = 0;
          const double gap = pl.n[0] * x(i, 0) + pl.n[1] * x(i, 1) + pl.n[2] * x(i, 2) - pl.d;
          const double vn =
              dt > 0.0 ? pl.n[0] * v(i, 0) + pl.n[1] * v(i, 1) + pl.n[2] * v(i, 2) : 0.0;
          if (gap + dt * vn <= tol) {
            for (int d = 0; d < 3; ++d) nn[d] = pl.n[d];
            if (dt > 0.0)
              for (int d = 0; d < 3; ++d) v(i, d) -= (vn + gap / dt) * pl.n[d];
            ++touching;
          }
          const double up = x(i, pl.up), vu = dt > 0.0 ? v(i, pl.up) : 0.0;
          const bool below = up + dt * vu <= pl.lo + tol, above = up + dt * vu >= pl.hi - tol;
          if (below || above) {
            // A plate (its position at the end of the step): parallel to the ground when the
            // ground's normal is the up axis.
            if (touching == 0 || nn[pl.up] < 1.0 - 1e-12) ++touching;
            for (int d = 0; d < 3; ++d) nn[d] = d == pl.up ? 1.0 : 0.0;
            if (dt > 0.0) v(i, pl.up) = ((below ? pl.lo : pl.hi) - up) / dt;
          }
          w(i) = pinned(i) || touching > 1 ? 0.0 : 1.0 / mass(i);
          for (int d = 0; d < 3; ++d) nrm(i, d) = nn[d];
        });
  }

  /// The element volumes, their gradients, the one-ring volumes and B at x.
  void update_volumes(const Nodes& x) {
    kernels::solid::tet_volume_gradients(exec_, tets_, x, vol_, grad_);
    kernels::solid::node_volumes(exec_, tets_, vol_, V_);
    kernels::solid::assemble_volume_gradient(exec_, grad_, B_);
  }

  /// out = s (V_0 - V) (s = 1: the position correction's right-hand side).
  void volume_difference(double s, const Scalars& out) {
    const auto V0 = V0_, V = V_;
    Kokkos::parallel_for(
        "amphora::solid::volume::difference", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i) { out(i) = s * (V0(i) - V(i)); });
  }

  /// out = B W B^T in.
  void apply_operator(const Scalars& in, const Scalars& out) {
    kernels::solid::volume_gradient_transpose_weighted(exec_, B_, w_, normal_, in, u_);
    kernels::solid::volume_gradient_matrix_apply(exec_, B_, u_, out);
  }

  /// y += W B^T q (q from the last solve).
  void correct(const Nodes& y) {
    kernels::solid::volume_gradient_transpose_weighted(exec_, B_, w_, normal_, q_, u_);
    const auto u = u_;
    Kokkos::parallel_for(
        "amphora::solid::volume::correct", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i) {
          for (int d = 0; d < 3; ++d) y(i, d) += u(i, d);
        });
  }

  /// q = (B W B^T)^-1 rhs by conjugate residuals preconditioned with its diagonal, from q =
  /// `guess`, to cr_tolerance |rhs| or the round-off level `floor`; returns the iterations
  /// (cr_converged_ says whether it got there). Preconditioned CR as in Saad, Iterative
  /// Methods for Sparse Linear Systems (2003), algorithm 9.2 with the M^-1 inner product.
  int solve(double floor, const Scalars& guess) {
    using kernels::blas1::axpby;
    using kernels::blas1::dot;
    diagonal();
    Kokkos::deep_copy(exec_, q_, guess);
    apply_operator(q_, r_);
    axpby(exec_, 1.0, rhs_, -1.0, r_);  // r = rhs - A q
    const double target = std::max(floor, o_.cr_tolerance * std::sqrt(dot(exec_, rhs_, rhs_)));
    precondition(r_, z_);
    apply_operator(z_, Ar_);
    Kokkos::deep_copy(exec_, p_, z_);
    Kokkos::deep_copy(exec_, Ap_, Ar_);
    double zAz = dot(exec_, z_, Ar_), rr = dot(exec_, r_, r_);
    int it = 0;
    cr_converged_ = true;
    while (std::sqrt(rr) > target) {
      const double ApMAp = precondition_dot(Ap_, y_);
      if (it >= o_.max_cr || !(zAz > 0.0) || !(ApMAp > 0.0)) {  // a residual W cannot reach
        cr_converged_ = false;
        break;
      }
      rr = advance(zAz / ApMAp);
      apply_operator(z_, Ar_);
      const double zAz_new = dot(exec_, z_, Ar_);
      new_directions(zAz_new / zAz);
      zAz = zAz_new;
      ++it;
    }
    Kokkos::deep_copy(exec_, guess, q_);
    return it;
  }

  /// y = D^-1 a; returns a . y.
  double precondition_dot(const Scalars& a, const Scalars& y) {
    const auto D = diag_;
    double s = 0.0;
    Kokkos::parallel_reduce(
        "amphora::solid::volume::precondition_dot", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i, double& acc) {
          y(i) = D(i) > 0.0 ? a(i) / D(i) : a(i);
          acc += a(i) * y(i);
        },
        s);
    return s;
  }

  /// q += alpha p, r -= alpha Ap, z -= alpha y; returns r . r.
  double advance(double alpha) {
    const auto q = q_, r = r_, z = z_, p = p_, Ap = Ap_, y = y_;
    double s = 0.0;
    Kokkos::parallel_reduce(
        "amphora::solid::volume::advance", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i, double& acc) {
          q(i) += alpha * p(i);
          r(i) -= alpha * Ap(i);
          z(i) -= alpha * y(i);
          acc += r(i) * r(i);
        },
        s);
    return s;
  }

  /// p = z + beta p, Ap = Az + beta Ap.
  void new_directions(double beta) {
    const auto z = z_, p = p_, Az = Ar_, Ap = Ap_;
    Kokkos::parallel_for(
        "amphora::solid::volume::new_directions", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i) {
          p(i) = z(i) + beta * p(i);
          Ap(i) = Az(i) + beta * Ap(i);
        });
  }

  /// D = the diagonal of B W B^T (the preconditioner).
  void diagonal() { kernels::solid::volume_operator_diagonal(exec_, B_, w_, normal_, diag_); }

  /// z = D^-1 r (z = r where D is zero: a node no free node can move).
  void precondition(const Scalars& r, const Scalars& z) {
    const auto D = diag_;
    Kokkos::parallel_for(
        "amphora::solid::volume::precondition", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i) { z(i) = D(i) > 0.0 ? r(i) / D(i) : r(i); });
  }

  /// max_i |V_i - V_0i| / V_0i.
  double relative_error() {
    const auto V0 = V0_, V = V_;
    double e = 0.0;
    Kokkos::parallel_reduce(
        "amphora::solid::volume::error", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i, double& acc) {
          const double r = kernels::math::abs(V(i) - V0(i)) / V0(i);
          acc = r > acc ? r : acc;
        },
        Kokkos::Max<double>(e));
    return e;
  }

  /// max_i |a_i| / V_0i.
  double relative_max(const Scalars& a) {
    const auto V0 = V0_;
    double e = 0.0;
    Kokkos::parallel_reduce(
        "amphora::solid::volume::rate", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i, double& acc) {
          const double r = kernels::math::abs(a(i)) / V0(i);
          acc = r > acc ? r : acc;
        },
        Kokkos::Max<double>(e));
    return e;
  }

  /// max_i |v_i|.
  double max_speed(const Nodes& v) {
    double m = 0.0;
    Kokkos::parallel_reduce(
        "amphora::solid::volume::max_speed", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i, double& acc) {
          const double s = v(i, 0) * v(i, 0) + v(i, 1) * v(i, 1) + v(i, 2) * v(i, 2);
          acc = s > acc ? s : acc;
        },
        Kokkos::Max<double>(m));
    return std::sqrt(m);
  }

  int n() const { return static_cast<int>(V0_.extent(0)); }

 private:
  VolumeOptions o_;
  ExecSpace exec_;
  Tets tets_;
  Scalars V0_, V_, rhs_, target_, q_, r_, z_, y_, p_, Ar_, Ap_, w_, diag_, vol_;
  Scalars q_position_, q_velocity_;  ///< the last solutions, the next solves' first guesses
  Nodes normal_, u_;
  Kokkos::View<double* [4][3], Mem> grad_;
  kernels::solid::VolumeGradientMatrix<Mem> B_;
  double volume_norm_ = 0.0;  ///< |V_0|_2: the scale of the position solves' round-off
  double length_ = 0.0;       ///< the cube root of the mean one-ring volume
  bool cr_converged_ = true;
};

}  // namespace amphora::physics::solid_fem
