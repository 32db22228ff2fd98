#pragma once
// A deformable solid on linear tetrahedra with the invertible hyperelastic models (Irving,
// Teran & Fedkiw, SCA 2004): lumped masses, the element forces of kernels/solid/tet_forces,
// and the explicit symplectic step (leapfrog in its velocity-Verlet form, so velocities and
// positions share a time and an undamped run conserves energy to O(dt^2)) with gravity,
// mass-proportional damping, pinned nodes, a ground plane and moving plates; optionally the
// per-node volume projection (volume_projection.hpp) and multiplicative plasticity
// (kernels/solid/plastic_flow.hpp) after each step.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/solid/node_update.hpp"
#include "kernels/solid/plastic_flow.hpp"
#include "kernels/solid/tet_forces.hpp"
#include "mesh/tet/tet_mesh.hpp"
#include "physics/solid_fem/backward_euler.hpp"
#include "physics/solid_fem/volume_projection.hpp"

namespace amphora::physics::solid_fem {

using kernels::solid::Hyperelastic;
using kernels::solid::Material;

struct TetSolidOptions {
  Material material;
  double density = 1.0;
  double gravity[3] = {0.0, 0.0, 0.0};
  double damping = 0.0;    ///< mass-proportional rate alpha [1/s]
  double viscosity = 0.0;  ///< Kelvin-Voigt eta [Pa s]: S = eta dC/dt (explicit stepping only)
  double floor = -std::numeric_limits<double>::infinity();  ///< the ground's height at x = y = 0
  double floor_tilt = 0.0;  ///< the ground's slope about the y axis [rad] (a ramp down to +x)
  double friction = 0.0;    ///< Coulomb coefficient of the ground and the plates
  bool implicit = false;    ///< backward Euler (Newton-CG) instead of the explicit step
  NewtonOptions newton;
  bool volume_preserving = false;  ///< the per-node volume projection after each step
  VolumeOptions volume;
  kernels::solid::PlasticFlow plastic;  ///< yield 0: elastic
};

/// Lame parameters from Young's modulus and Poisson's ratio; the compressible models need
/// nu in (-1, 0.5) (std::invalid_argument otherwise).
inline Material material_from_young_poisson(Hyperelastic model, double young, double poisson,
                                            double s_clamp = 0.25) {
  if (!(young > 0.0)) throw std::invalid_argument("solid_fem: Young's modulus must be > 0");
  if (!(poisson > -1.0 && poisson < 0.5))
    throw std::invalid_argument("solid_fem: Poisson's ratio " + std::to_string(poisson) +
                                " is outside (-1, 0.5), the range of the compressible models");
  const double mu = young / (2.0 * (1.0 + poisson));
  const double lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  return Material{model, mu, lambda, s_clamp};
}

template <class ExecSpace>
class TetSolid {
 public:
  using Mem = typename ExecSpace::memory_space;
  using Nodes = Kokkos::View<double* [3], Mem>;

  /// Throws std::invalid_argument listing inverted or degenerate rest elements, and for
  /// non-positive density or mu, or Poisson's ratio >= 0.5.
  TetSolid(const mesh::tet::TetMesh& rest, const TetSolidOptions& o,
           const ExecSpace& exec = ExecSpace())
      : o_(o), exec_(exec) {
    check_options(o);
    const auto views = mesh::tet::to_views<Mem>(rest);
    tets_ = views.tets;
    X_ = views.nodes;
    shapes_ = kernels::solid::tet_rest_shapes(exec_, X_, tets_);
    check_rest_volumes();
    for (int e = 0; e < rest.n_tets(); ++e) rest_volume_ += mesh::tet::tet_volume(rest, e);
    h_min_ = shortest_altitude(rest);
    x_ = Nodes("amphora::solid::x", rest.n_nodes());
    Kokkos::deep_copy(exec_, x_, X_);
    v_ = Nodes("amphora::solid::v", rest.n_nodes());
    f_ = Nodes("amphora::solid::f", rest.n_nodes());
    J_ = Kokkos::View<double*, Mem>("amphora::solid::J", rest.n_tets());
    pinned_ = Kokkos::View<char*, Mem>("amphora::solid::pinned", rest.n_nodes());
    lump_masses(rest.n_nodes());
    if (plastic()) start_plasticity();
  }

  /// The explicit limit dt <= h_min / c times `safety`, with c = sqrt(K / rho) for the stiffest
  /// uniaxial modulus K the model reaches: lambda + 2 mu at rest, or dP^_0/ds_0 at s = (s_clamp,
  /// 1, 1) if larger (neo-Hookean stiffens under compression: about 23x for lambda = 2 mu, so
  /// squashed runs need a ~5x smaller step than the rest state's), and with Kelvin-Voigt damping
  /// at most rho h_min^2 / (8 eta).
  double stable_dt(double safety = 0.5) const {
    const Material& m = o_.material;
    double K = m.lambda + 2.0 * m.mu;
    if (m.s_clamp > 0.0) {
      const kernels::solid::Vec3 s{{m.s_clamp, 1.0, 1.0}};
      K = std::max(K, kernels::solid::diagonal_stress(m, s).dP_ds(0, 0));
    }
    const double elastic = h_min_ / std::sqrt(K / o_.density);
    // the viscous stress' diffusion limit rho h^2 / (c eta): c = 8 keeps a factor 2 from the
    // measured threshold (docs/solid_fem.md)
    const double viscous = o_.density * h_min_ * h_min_ / (8.0 * o_.viscosity);
    return safety * (o_.viscosity > 0.0 ? std::min(elastic, viscous) : elastic);
  }

  /// Throws std::invalid_argument naming the limit when dt exceeds stable_dt(1) (explicit
  /// stepping only).
  void check_time_step(double dt) const {
    if (dt > 0.0 && (o_.implicit || dt <= stable_dt(1.0))) return;
    std::ostringstream s;
    s << "solid_fem: time step " << dt << " is outside (0, " << stable_dt(1.0)
      << "], the explicit limit h_min / c_p (h_min " << h_min_ << ")";
    if (o_.viscosity > 0.0) s << " or the viscous one rho h_min^2 / (8 eta)";
    throw std::invalid_argument(s.str());
  }

  /// One step of dt: explicit, or backward Euler where the options ask for it.
  void step(double dt) {
    if (o_.implicit) return step_implicit(dt);
    if (!forces_current_) update_forces();
    kernels::solid::NodeKick k;
    k.h = 0.5 * dt;
    for (int d = 0; d < 3; ++d) k.gravity[d] = o_.gravity[d];
    k.alpha = o_.damping;
    kernels::solid::kick(exec_, k, mass_, pinned_, f_, v_);
    start_volume_report();
    project_volumes(false, true, dt);  // the drift's velocities, then the new positions
    kernels::solid::drift(exec_, dt, planes(), pinned_, v_, x_);
    project_volumes(true, false);
    plastic_flow();
    update_forces();
    kernels::solid::kick(exec_, k, mass_, pinned_, f_, v_);
    time_ += dt;
  }
  /// One backward-Euler step of dt (backward_euler.hpp); the ground and the plates then act
  /// on the new positions as in the explicit drift (outside the Newton solve).
  void step_implicit(double dt) {
    if (!implicit_) {
      // Round-off's level of the gradient: 1e-10 of the force a unit strain puts on an
      // element, summed over the nodes in quadrature.
      NewtonOptions n = o_.newton;
      const double h = std::cbrt(rest_volume_ / n_tets()),
                   K = o_.material.lambda + 2.0 * o_.material.mu;
      n.absolute = std::max(n.absolute, 1e-10 * K * h * h * std::sqrt(double(n_nodes())));
      implicit_ = std::make_unique<BackwardEuler<ExecSpace>>(n_nodes(), n_tets(), n, exec_);
    }
    ImplicitSystem<Mem> s{o_.material, shapes_, tets_, mass_, pinned_, external_};
    for (int d = 0; d < 3; ++d) s.gravity[d] = o_.gravity[d];
    s.damping = o_.damping;
    newton_ = implicit_->step(s, dt, x_, v_);
    Kokkos::deep_copy(exec_, x_, implicit_->start());
    kernels::solid::drift(exec_, dt, planes(), pinned_, v_, x_);
    start_volume_report();
    project_volumes(true, true);
    plastic_flow();
    update_forces();
    time_ += dt;
  }
  /// The per-node volume projection (volume_projection.hpp) where the options ask for it:
  /// the velocity projection and the position correction, either or both, added to the
  /// step's report. Velocities alone are projected before a drift of dt.
  void project_volumes(bool positions, bool velocities, double dt = 0.0) {
    if (!o_.volume_preserving) return;
    if (!volume_) {
      VolumeOptions v = o_.volume;
      if (v.contact_gap == 0.0) v.contact_gap = 1e-9 * h_min_;
      volume_ = std::make_unique<VolumeProjection<ExecSpace>>(tets_, X_, v, exec_);
    }
    VolumeReport& rep = volume_report_;
    if (velocities && !positions) {  // before the drift of dt: its contacts held
      volume_->set_weights(mass_, pinned_, planes(), x_, v_, dt);
      volume_->project_velocities(x_, v_, rep);
    }
    volume_->set_weights(mass_, pinned_, planes(), x_, v_, 0.0);
    if (positions) {
      const VolumeReport r = volume_->correct_positions(x_);
      rep.corrections = r.corrections, rep.error_before = r.error_before, rep.error = r.error;
      rep.cr_iterations += r.cr_iterations;
      rep.converged = rep.converged && r.converged;
    }
    if (velocities && positions) volume_->project_velocities(x_, v_, rep);  // at the new x
  }
  bool plastic() const { return o_.plastic.yield > 0.0; }
  /// F_p = I and the mesh's own rest shapes kept (plasticity rewrites the forces' copy).
  void start_plasticity() {
    Fp_ = Kokkos::View<double* [3][3], Mem>("amphora::solid::Fp", n_tets());
    Dm0_inv_ = Kokkos::View<double* [3][3], Mem>("amphora::solid::Dm0_inv", n_tets());
    Kokkos::deep_copy(exec_, Dm0_inv_, shapes_.Dm_inv);
    auto h = Kokkos::create_mirror_view(Fp_);
    for (int e = 0; e < n_tets(); ++e)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) h(e, i, j) = i == j ? 1.0 : 0.0;
    Kokkos::deep_copy(exec_, Fp_, h);
  }
  /// The plastic flow at the current positions (plastic models only).
  void plastic_flow() {
    if (!plastic()) return;
    kernels::solid::tet_plastic_flow(exec_, o_.plastic, Dm0_inv_, tets_, x_, Fp_, shapes_.Dm_inv);
    forces_current_ = false;
  }
  /// F_p per element (plastic models; empty otherwise).
  const Kokkos::View<double* [3][3], Mem>& plastic_deformation() const { return Fp_; }
  /// After writing plastic_deformation() (a restart): the rest shapes follow it.
  void plastic_deformation_changed() {
    kernels::solid::tet_plastic_rest_shapes(exec_, Dm0_inv_, Fp_, shapes_.Dm_inv);
    forces_current_ = false;
  }
  /// The largest Hencky strain norm of F_p over the elements (0 for elastic models).
  double max_plastic_strain() const {
    return plastic() ? kernels::solid::max_plastic_strain(exec_, Fp_) : 0.0;
  }
  /// A new step's volume report.
  void start_volume_report() {
    volume_report_ = VolumeReport{};
    volume_report_.converged = true;
  }
  /// The last step's volume projection (volume_preserving).
  const VolumeReport& volume_report() const { return volume_report_; }
  /// The last implicit step's Newton iterations, CG iterations and residuals.
  const NewtonReport& newton_report() const { return newton_; }

  /// Plates normal to z that hold the body between them in the coming steps (their positions
  /// at the end of the step and their velocities; the ground plane in p is not used).
  void set_plates(const kernels::solid::BoundingPlanes& p) { plates_ = p; }
  /// The ground (options) and the plates (set_plates) for the drift.
  kernels::solid::BoundingPlanes planes() const {
    kernels::solid::BoundingPlanes p = plates_;
    p.n[0] = std::sin(o_.floor_tilt), p.n[1] = 0.0, p.n[2] = std::cos(o_.floor_tilt);
    p.d = std::isfinite(o_.floor) ? o_.floor * p.n[2] : -1e300;
    p.friction = o_.friction;
    return p;
  }
  /// Constant nodal loads [N] added to the elastic forces from now on (an empty View: none).
  void set_external_forces(const Nodes& f) {
    external_ = f;
    forces_current_ = false;
  }
  /// The elastic forces (plus the nodal loads) and det F at the current positions.
  void update_forces() {
    if (external_.extent(0) > 0)
      Kokkos::deep_copy(exec_, f_, external_);
    else
      Kokkos::deep_copy(exec_, f_, 0.0);
    kernels::solid::tet_forces(exec_, o_.material, shapes_, tets_, x_, f_, J_);
    if (o_.viscosity > 0.0)
      kernels::solid::tet_damping_forces(exec_, o_.viscosity, shapes_, tets_, x_, v_, f_);
    forces_current_ = true;
  }

  double kinetic_energy() const {
    const auto m = mass_;
    const auto v = v_;
    double e = 0.0;
    Kokkos::parallel_reduce(
        "amphora::solid::kinetic_energy", kernels::RangePolicy<ExecSpace>(exec_, 0, n_nodes()),
        KOKKOS_LAMBDA(const int i, double& sum) {
          sum += 0.5 * m(i) * (v(i, 0) * v(i, 0) + v(i, 1) * v(i, 1) + v(i, 2) * v(i, 2));
        },
        e);
    return e;
  }
  double elastic_energy() const {
    return kernels::solid::tet_elastic_energy(exec_, o_.material, shapes_, tets_, x_);
  }
  /// The smallest det F over the elements (at the last force evaluation).
  double min_det_F() {
    if (!forces_current_) update_forces();
    double m = 0.0;
    const auto J = J_;
    Kokkos::parallel_reduce(
        "amphora::solid::min_det_F", kernels::RangePolicy<ExecSpace>(exec_, 0, n_tets()),
        KOKKOS_LAMBDA(const int e, double& acc) { acc = J(e) < acc ? J(e) : acc; },
        Kokkos::Min<double>(m));
    return m;
  }

  /// The deformed volume sum_e W_e det F_e (at the last force evaluation).
  double volume() {
    if (!forces_current_) update_forces();
    const auto J = J_;
    const auto W = shapes_.volume;
    double v = 0.0;
    Kokkos::parallel_reduce(
        "amphora::solid::volume", kernels::RangePolicy<ExecSpace>(exec_, 0, n_tets()),
        KOKKOS_LAMBDA(const int e, double& sum) { sum += W(e) * J(e); }, v);
    return v;
  }
  double rest_volume() const { return rest_volume_; }
  /// det F per element (at the last force evaluation).
  const Kokkos::View<double*, Mem>& det_F() const { return J_; }

  /// The first node with a non-finite force, position or velocity; -1 if none.
  int first_nonfinite_node() const {
    const auto x = x_, v = v_, f = f_;
    const int none = n_nodes();
    int first = none;
    Kokkos::parallel_reduce(
        "amphora::solid::first_nonfinite_node",
        kernels::RangePolicy<ExecSpace>(exec_, 0, n_nodes()),
        KOKKOS_LAMBDA(const int i, int& acc) {
          bool ok = true;
          for (int d = 0; d < 3; ++d)
            ok = ok && kernels::math::isfinite(x(i, d)) && kernels::math::isfinite(v(i, d)) &&
                 kernels::math::isfinite(f(i, d));
          if (!ok && i < acc) acc = i;
        },
        Kokkos::Min<int>(first));
    return first >= none ? -1 : first;  // Min<int> starts from INT_MAX
  }

  int n_nodes() const { return static_cast<int>(x_.extent(0)); }
  int n_tets() const { return static_cast<int>(tets_.extent(0)); }
  double time() const { return time_; }
  /// Positions and velocities; a caller that changes positions calls update_forces() after.
  const Nodes& positions() const { return x_; }
  const Nodes& velocities() const { return v_; }
  /// The forces at the last update_forces() (elastic, damping and nodal loads; no gravity).
  const Nodes& forces() const { return f_; }
  const Nodes& rest_positions() const { return X_; }
  const Kokkos::View<char*, Mem>& pinned() const { return pinned_; }
  const Kokkos::View<double*, Mem>& masses() const { return mass_; }
  const Kokkos::View<int* [4], Mem>& tets() const {
    return tets_;
  } const TetSolidOptions& options() const {
    return o_;
  }

  /// Row-sum lumped masses (public: CUDA forbids extended lambdas in private members).
  /// Each element gives rho W / 4 to its nodes.
  void lump_masses(int n) {
    mass_ = Kokkos::View<double*, Mem>("amphora::solid::mass", n);
    const auto m = mass_;
    const auto vol = shapes_.volume;
    const auto t = tets_;
    const double rho = o_.density;
    Kokkos::parallel_for(
        "amphora::solid::lump_masses", kernels::RangePolicy<ExecSpace>(exec_, 0, n_tets()),
        KOKKOS_LAMBDA(const int e) {
          for (int c = 0; c < 4; ++c) Kokkos::atomic_add(&m(t(e, c)), 0.25 * rho * vol(e));
        });
  }

 private:
  static void check_options(const TetSolidOptions& o) {
    const Material& m = o.material;
    auto fail = [](const std::string& what) { throw std::invalid_argument("solid_fem: " + what); };
    if (!(o.density > 0.0)) fail("density must be > 0");
    if (!(m.mu > 0.0)) fail("mu must be > 0");
    const double nu = m.lambda / (2.0 * (m.lambda + m.mu));  // Poisson's ratio
    if (!(m.lambda >= 0.0) || !(nu < 0.5))
      fail("Poisson's ratio " + std::to_string(nu) +
           " is outside [0, 0.5) (the compressible models need lambda finite and >= 0)");
    if (!(o.damping >= 0.0)) fail("damping must be >= 0");
    if (!(o.viscosity >= 0.0)) fail("viscosity must be >= 0");
    if (!(o.friction >= 0.0)) fail("friction must be >= 0");
    if (o.friction > 0.0 && o.volume_preserving)
      fail(
          "friction is not built for the volume projection's contacts; set friction = 0 or "
          "volume_preserving = false");
    if (o.viscosity > 0.0 && o.implicit)
      fail(
          "viscosity (Kelvin-Voigt damping) needs the explicit integrator; use damping "
          "(mass-proportional) with backward_euler");
    if (!(o.plastic.yield >= 0.0)) fail("the plastic yield strain must be >= 0");
    if (!(o.plastic.clamp > 1.0)) fail("the plastic clamp must be > 1");
  }

  /// Lists the elements of non-positive rest volume (at most ten named).
  void check_rest_volumes() const {
    const auto vol = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), shapes_.volume);
    std::vector<long> bad;
    for (size_t e = 0; e < vol.extent(0); ++e)
      if (!(vol(e) > 0.0)) bad.push_back(static_cast<long>(e));
    if (bad.empty()) return;
    std::ostringstream s;
    s << "solid_fem: " << bad.size() << " inverted or degenerate rest element(s):";
    for (size_t i = 0; i < bad.size() && i < 10; ++i) s << " " << bad[i];
    if (bad.size() > 10) s << " ...";
    throw std::invalid_argument(s.str());
  }

  /// The smallest element altitude 3 V / (largest face area): the length a wave crosses in a
  /// step (a sliver's, not its edges').
  static double shortest_altitude(const mesh::tet::TetMesh& m) {
    double h = std::numeric_limits<double>::infinity();
    for (int e = 0; e < m.n_tets(); ++e) {
      const auto& t = m.tets[e];
      double largest = 0.0;
      for (int skip = 0; skip < 4; ++skip) {
        const auto& a = m.nodes[t[(skip + 1) % 4]];
        const auto& b = m.nodes[t[(skip + 2) % 4]];
        const auto& c = m.nodes[t[(skip + 3) % 4]];
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                             u[0] * w[1] - u[1] * w[0]};
        largest = std::max(largest, 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
      }
      h = std::min(h, 3.0 * mesh::tet::tet_volume(m, e) / largest);
    }
    return h;
  }

  TetSolidOptions o_;
  ExecSpace exec_;
  Kokkos::View<int* [4], Mem> tets_;
  Nodes X_, x_, v_, f_, external_;
  kernels::solid::TetRestShapes<Mem> shapes_;
  Kokkos::View<double*[3][3], Mem> Fp_, Dm0_inv_;  ///< plastic models: F_p, the mesh's D_m^-1
  Kokkos::View<double*, Mem> J_, mass_;
  Kokkos::View<char*, Mem> pinned_;
  kernels::solid::BoundingPlanes plates_;
  std::unique_ptr<BackwardEuler<ExecSpace>> implicit_;
  NewtonReport newton_;
  std::unique_ptr<VolumeProjection<ExecSpace>> volume_;
  VolumeReport volume_report_;
  double h_min_ = 0.0, time_ = 0.0, rest_volume_ = 0.0;
  bool forces_current_ = false;
};

}  // namespace amphora::physics::solid_fem
