#include "physics/solid_fem/solid_module.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "mesh/tet/gmsh_reader.hpp"
#include "mesh/tet/shape_meshes.hpp"
#include "physics/solid_fem/tet_solid.hpp"

namespace amphora::physics::solid_fem {
// A named namespace, not an anonymous one (CUDA extended lambdas; Kokkos issue #1547).
namespace solid_module_detail {

using Exec = kernels::DefaultExecSpace;

Hyperelastic model_of(const std::string& name) {
  if (name == "corotated") return Hyperelastic::corotated;
  if (name == "st_venant_kirchhoff") return Hyperelastic::st_venant_kirchhoff;
  return Hyperelastic::neo_hookean;
}

/// A mesh file, refused (naming the place) when its boundary is not a closed manifold.
mesh::tet::TetMesh read_mesh(const std::string& path) {
  mesh::tet::TetMesh m = mesh::tet::read_gmsh(path);
  try {
    mesh::tet::boundary_faces(m);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + ": " + e.what());
  }
  return m;
}

/// The body: a mesh file, or the box, ball, torus or cylinder of the scene's sizes (the
/// curved ones resting on z = 0; the cylinder along x from 0 to length).
mesh::tet::TetMesh shape_mesh(const Parameters& p) {
  if (!p.string("mesh").empty()) return read_mesh(p.string("mesh"));
  const int n = static_cast<int>(p.integer("cells"));
  const double r = p.real("radius");
  if (p.string("shape") == "ball") return mesh::tet::ball_tet_mesh(r, n, {0.0, 0.0, r});
  if (p.string("shape") == "torus") {
    if (!(p.real("ring_radius") > r))
      throw std::invalid_argument("solid_fem: the torus needs ring_radius > radius (now " +
                                  std::to_string(p.real("ring_radius")) + " and " +
                                  std::to_string(r) + ")");
    return mesh::tet::torus_tet_mesh(p.real("ring_radius"), r, n, {0.0, 0.0, r});
  }
  if (p.string("shape") == "cylinder")
    return mesh::tet::cylinder_tet_mesh(r, p.real("length"), n, {0.5 * p.real("length"), 0.0, r});
  const double L = p.real("length"), W = p.real("width"), H = p.real("height");
  // Cells along x, y and z in proportion to the box's sides (at least one each).
  auto count = [&](double side) {
    return std::max(1, static_cast<int>(std::lround(n * side / L)));
  };
  return mesh::tet::box_tet_mesh({n, count(W), count(H)}, {0.0, -0.5 * W, 0.0}, {L, 0.5 * W, H});
}

class SolidModule final : public Module {
 public:
  SolidModule(const Parameters& p, const Communicator& comm) : mesh_(shape_mesh(p)) {
    if (comm.size() > 1)
      throw std::invalid_argument("solid_fem runs on one rank; run without mpirun or with -n 1");
    TetSolidOptions o;
    o.material = material_from_young_poisson(model_of(p.string("model")), p.real("young"),
                                             p.real("poisson"), p.real("s_clamp"));
    o.density = p.real("density");
    o.gravity[2] = -p.real("gravity");
    o.damping = p.real("damping");
    o.viscosity = p.real("viscosity");
    o.implicit = p.string("integrator") == "backward_euler";
    o.newton.tolerance = p.real("newton_tolerance");
    o.newton.max_iterations = static_cast<int>(p.integer("newton_max_iterations"));
    o.volume_preserving = p.boolean("volume_preserving");
    o.volume.tolerance = p.real("volume_tolerance");
    o.volume.recovery_time = p.real("volume_recovery_time");
    o.plastic.yield = p.real("plastic_yield");
    o.plastic.clamp = p.real("plastic_clamp");
    o.floor = p.real("floor");
    o.floor_tilt = p.real("floor_tilt") * 3.14159265358979323846 / 180.0;
    o.friction = p.real("friction");
    solid_ = std::make_unique<TetSolid<Exec>>(mesh_, o);
    squash_and_pin(p.real("squash"), p.boolean("pin_x0"));
    if (p.real("plate_gap") < 1.0) plates_ = Plates{p.real("plate_gap"), p.real("plate_speed")};
    // Euler-Bernoulli's cantilever under its own weight: q L^4 / (8 E I) = 1.5 rho g L^4 / (E H^2)
    // for the box (small deflections; shear adds (H/L)^2 / 10 of it and less).
    if (!free_end_.empty() && p.string("mesh").empty() && p.string("shape") == "box" &&
        o.gravity[2] < 0.0)
      beam_sag_ = 1.5 * o.density * p.real("gravity") * std::pow(p.real("length"), 4) /
                  (p.real("young") * p.real("height") * p.real("height"));
  }

  /// z -> c + s (z - c) about the centre height c; the x = min face pinned where asked.
  void squash_and_pin(double s, bool pin) {
    double zmin = 1e300, zmax = -1e300, xmin = 1e300, xmax = -1e300;
    for (const auto& q : mesh_.nodes) {
      zmin = std::min(zmin, q[2]), zmax = std::max(zmax, q[2]);
      xmin = std::min(xmin, q[0]), xmax = std::max(xmax, q[0]);
    }
    const double c = 0.5 * (zmin + zmax), tol = 1e-9 * (xmax - xmin);
    centre_z_ = c, height_ = zmax - zmin;
    auto x = Kokkos::create_mirror(solid_->positions());
    auto pinned = Kokkos::create_mirror(solid_->pinned());
    for (int i = 0; i < mesh_.n_nodes(); ++i) {
      const auto& q = mesh_.nodes[i];
      x(i, 0) = q[0], x(i, 1) = q[1], x(i, 2) = c + s * (q[2] - c);
      pinned(i) = pin && q[0] <= xmin + tol;
      if (pin && q[0] >= xmax - tol) free_end_.push_back(i);
    }
    Kokkos::deep_copy(solid_->positions(), x);
    Kokkos::deep_copy(solid_->pinned(), pinned);
    solid_->update_forces();
  }

  std::string name() const override { return "solid_fem"; }
  double stable_dt() const override { return solid_->stable_dt(1.0); }
  void set_time_step(double dt) override { solid_->check_time_step(dt); }
  void advance(double t, double dt) override {
    if (plates_.gap < 1.0) solid_->set_plates(plates_at(t, dt));
    solid_->step(dt);
    const NewtonReport& r = solid_->newton_report();
    if (solid_->options().implicit && !r.converged && failure_.empty()) {
      std::ostringstream m;
      m << "the Newton solve did not converge (gradient " << r.residual << " of "
        << r.initial_residual << " after " << r.iterations << " iterations)";
      failure_ = m.str();
    }
    const VolumeReport& v = solid_->volume_report();
    if (solid_->options().volume_preserving && !v.converged && failure_.empty()) {
      std::ostringstream m;
      m << "the volume projection did not converge (per-node volume error " << v.error << " after "
        << v.corrections << " corrections, " << v.cr_iterations
        << " conjugate-residual iterations)";
      failure_ = m.str();
    }
  }
  long long work_per_step() const override { return solid_->n_tets(); }
  std::string work_unit() const override { return "element-steps"; }
  /// The cantilever: its sag's relative error against beam theory; squashed between plates:
  /// the shape error after release; otherwise the volume error.
  std::string error_diagnostic() const override {
    return beam_sag_ > 0.0 ? "sag_error" : plates_.gap < 1.0 ? "shape_error" : "volume_error";
  }

  std::vector<OutputBlock> output(double) const override;
  Diagnostics diagnostics(double) const override;
  /// Non-finite values, or a failed Newton solve or volume projection (reported at node 0),
  /// stop the run.
  std::optional<NonFiniteReport> find_nonfinite() const override {
    int i = solid_->first_nonfinite_node();
    if (i < 0 && failure_.empty()) return std::nullopt;
    NonFiniteReport r;
    r.field = "position/velocity/force";
    r.block = "solid";
    r.reason = solid_->options().material.s_clamp > 0.0
                   ? ""
                   : "non-finite value (an element inverted: the standard model has no "
                     "stress there; set s_clamp > 0 for invertible FEM)";
    if (i < 0) i = 0, r.reason = failure_;
    r.index = i;
    r.point = {mesh_.nodes[i][0], mesh_.nodes[i][1], mesh_.nodes[i][2]};  // rest position
    return r;
  }
  std::vector<StateBlock> state() const override;
  void restore(const std::vector<StateBlock>& blocks) override;
  void restore_plastic(const std::vector<double>& data);
  std::vector<std::string> owned_blocks() const override { return {"solid"}; }

 private:
  static std::vector<double> flat(const TetSolid<Exec>::Nodes& v) {
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
    std::vector<double> out(3 * h.extent(0));
    for (size_t i = 0; i < h.extent(0); ++i)
      for (int d = 0; d < 3; ++d) out[3 * i + d] = h(i, d);
    return out;
  }

  /// The plates' closest gap (a fraction of the rest height; 1: no plates) and speed.
  struct Plates {
    double gap = 1.0, speed = 0.0;
  };
  /// The plates about the body's centre height at the end of the step from t: closing at
  /// `speed` each until the gap is reached, then opening as fast; gone once back apart.
  kernels::solid::BoundingPlanes plates_at(double t, double dt) const {
    const double travel = 0.5 * height_ * (1.0 - plates_.gap), t1 = travel / plates_.speed;
    kernels::solid::BoundingPlanes b;
    const double end = t + dt;
    if (end >= 2.0 * t1) return b;
    const double half = 0.5 * height_ - plates_.speed * (end <= t1 ? end : 2.0 * t1 - end);
    const double v = t + 0.5 * dt < t1 ? plates_.speed : -plates_.speed;
    b.lo = centre_z_ - half, b.v_lo = v;
    b.hi = centre_z_ + half, b.v_hi = -v;
    return b;
  }
  /// The largest distance of a node from the best rigid motion of the rest shape (Kabsch's
  /// fit about the centre of mass), over half the rest shape's largest extent.
  double shape_error(const std::vector<double>& x) const;

  mesh::tet::TetMesh mesh_;
  std::unique_ptr<TetSolid<Exec>> solid_;
  Plates plates_;
  std::string failure_;  ///< why the last implicit solve failed; empty: it did not
  double centre_z_ = 0.0, height_ = 0.0;
  std::vector<int> free_end_;  ///< the nodes of the x = max face of a pinned body
  double beam_sag_ = 0.0;      ///< Euler-Bernoulli's sag of the pinned box; 0: not a cantilever
};

Diagnostics SolidModule::diagnostics(double) const {
  const std::vector<double> x = flat(solid_->positions());
  auto m = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solid_->masses());
  double mass = 0.0, mz = 0.0, sag = 0.0;
  for (int i = 0; i < mesh_.n_nodes(); ++i) mass += m(i), mz += m(i) * x[3 * i + 2];
  for (int i : free_end_) sag += x[3 * i + 2] - mesh_.nodes[i][2];
  const double g = -solid_->options().gravity[2];
  const double kinetic = solid_->kinetic_energy(), elastic = solid_->elastic_energy();
  auto& s = *solid_;
  Diagnostics d = {{"kinetic_energy", kinetic},
                   {"elastic_energy", elastic},
                   {"total_energy", kinetic + elastic + g * mz},
                   {"min_det_F", s.min_det_F()},
                   {"volume_error", s.volume() / s.rest_volume() - 1.0},
                   {"centroid_z", mz / mass},
                   {"shape_error", shape_error(x)}};
  if (!free_end_.empty()) d.push_back({"free_end_dz", sag / double(free_end_.size())});
  if (s.options().implicit) {
    d.push_back({"newton_iterations", double(s.newton_report().iterations)});
    d.push_back({"cg_iterations", double(s.newton_report().cg_iterations)});
  }
  if (s.options().volume_preserving) {
    d.push_back({"node_volume_error", s.volume_report().error});
    d.push_back({"volume_cr_iterations", double(s.volume_report().cr_iterations)});
  }
  if (s.plastic()) d.push_back({"max_plastic_strain", s.max_plastic_strain()});
  if (beam_sag_ > 0.0) {
    const double ratio = -sag / double(free_end_.size()) / beam_sag_;
    d.push_back({"sag_beam_theory", beam_sag_});
    d.push_back({"sag_ratio", ratio});  // below 1: too stiff (locking)
    d.push_back({"sag_error", std::abs(ratio - 1.0)});
  }
  return d;
}

double SolidModule::shape_error(const std::vector<double>& x) const {
  auto m = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solid_->masses());
  const int n = mesh_.n_nodes();
  Eigen::Vector3d C = Eigen::Vector3d::Zero(), c = Eigen::Vector3d::Zero();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  double mass = 0.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d X(mesh_.nodes[i].data());
    C += m(i) * X, c += m(i) * Eigen::Vector3d(&x[3 * i]), mass += m(i);
    lo = lo.cwiseMin(X), hi = hi.cwiseMax(X);
  }
  C /= mass, c /= mass;
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i)
    H += m(i) * (Eigen::Vector3d(mesh_.nodes[i].data()) - C) *
         (Eigen::Vector3d(&x[3 * i]) - c).transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  const Eigen::Matrix3d R = svd.matrixV() * D * svd.matrixU().transpose();
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
    worst = std::max(
        worst,
        (Eigen::Vector3d(&x[3 * i]) - c - R * (Eigen::Vector3d(mesh_.nodes[i].data()) - C)).norm());
  return worst / (0.5 * (hi - lo).maxCoeff());
}

std::vector<OutputBlock> SolidModule::output(double) const {
  const std::vector<double> x = flat(solid_->positions()), v = flat(solid_->velocities());
  auto J = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solid_->det_F());
  OutputBlock b;
  b.name = "solid";
  const int n = mesh_.n_nodes();
  std::vector<double> u[3], speed(n);
  for (int i = 0; i < n; ++i) {
    b.x.push_back(x[3 * i]), b.y.push_back(x[3 * i + 1]), b.z.push_back(x[3 * i + 2]);
    for (int d = 0; d < 3; ++d) u[d].push_back(x[3 * i + d] - mesh_.nodes[i][d]);
    speed[i] =
        std::sqrt(v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]);
  }
  for (const auto& t : mesh_.tets)
    for (int c : t) b.tets.push_back(double(c));
  b.fields = {{"ux", u[0]},
              {"uy", u[1]},
              {"uz", u[2]},
              {"speed", speed},
              {"det_F", std::vector<double>(J.data(), J.data() + J.extent(0))}};
  return {b};
}

std::vector<StateBlock> SolidModule::state() const {
  StateBlock b{"solid", {{"x", flat(solid_->positions())}, {"v", flat(solid_->velocities())}}};
  if (solid_->plastic()) {
    auto h =
        Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solid_->plastic_deformation());
    std::vector<double> fp(9 * h.extent(0));
    for (size_t e = 0; e < h.extent(0); ++e)
      for (int k = 0; k < 9; ++k) fp[9 * e + k] = h(e, k / 3, k % 3);
    b.arrays.push_back({"Fp", fp});
  }
  return {b};
}

/// F_p from a checkpoint's "Fp" array (9 entries per element, row by row).
void SolidModule::restore_plastic(const std::vector<double>& data) {
  const auto& Fp = solid_->plastic_deformation();
  if (!solid_->plastic() || data.size() != 9 * Fp.extent(0))
    throw std::runtime_error(
        "solid_fem: the checkpoint's plastic deformation does not fit this "
        "scene (plastic_yield or the mesh differ)");
  auto h = Kokkos::create_mirror_view(Fp);
  for (size_t e = 0; e < h.extent(0); ++e)
    for (int k = 0; k < 9; ++k) h(e, k / 3, k % 3) = data[9 * e + k];
  Kokkos::deep_copy(Fp, h);
  solid_->plastic_deformation_changed();
}

void SolidModule::restore(const std::vector<StateBlock>& blocks) {
  for (const auto& b : blocks)
    for (const auto& [key, data] : b.arrays) {
      if (b.name == "solid" && key == "Fp") restore_plastic(data);
      if (b.name != "solid" || (key != "x" && key != "v")) continue;
      if (data.size() != 3 * size_t(mesh_.n_nodes()))
        throw std::runtime_error("solid_fem: the checkpoint's solid block does not fit this scene");
      const auto& view = key == "x" ? solid_->positions() : solid_->velocities();
      auto h = Kokkos::create_mirror(view);
      for (int i = 0; i < mesh_.n_nodes(); ++i)
        for (int d = 0; d < 3; ++d) h(i, d) = data[3 * i + d];
      Kokkos::deep_copy(view, h);
    }
  solid_->update_forces();
}

}  // namespace solid_module_detail

ParamTable parameter_table() {
  return {
      "solid_fem",
      "hyperelastic solid on linear tetrahedra, invertible FEM (Irving, Teran & Fedkiw 2004), "
      "explicit or backward Euler",
      {
          string_param("mesh", std::string(""),
                       "a Gmsh 4.1 ASCII file of linear tetrahedra (path from the working "
                       "directory); empty: the box below"),
          real_param("length", 1.0, "m", above(0.0), "box side (cylinder length) along x"),
          real_param("width", 1.0, "m", above(0.0), "box side along y"),
          real_param("height", 1.0, "m", above(0.0), "box side along z"),
          string_param("shape", std::string("box"),
                       "the body when no mesh file is given (the ball and the torus rest "
                       "on z = 0)",
                       {"box", "ball", "torus", "cylinder"}),
          real_param("radius", 0.05, "m", above(0.0),
                     "the ball's radius, the torus' tube's, the cylinder's"),
          real_param("ring_radius", 0.15, "m", above(0.0),
                     "the torus' ring radius (centre line), > radius"),
          int_param(
              "cells", 6, at_least(2) & at_most(200),
              "the box: lattice cubes along x (six tetrahedra each); the ball, torus, cylinder: "
              "cells across the (tube's) diameter (24 tetrahedra each)"),
          string_param("model", std::string("neo_hookean"), "the hyperelastic model",
                       {"neo_hookean", "corotated", "st_venant_kirchhoff"}),
          real_param("young", 1e5, "Pa", above(0.0), "Young's modulus"),
          real_param("poisson", 0.3, "1", above(-1.0) & below(0.5), "Poisson's ratio"),
          real_param("density", 1000.0, "kg/m^3", above(0.0), "mass density"),
          real_param("s_clamp", 0.25, "1", at_least(0.0) & below(1.0),
                     "singular values below it are extrapolated (invertible FEM); 0: the "
                     "standard model, which fails on inverted elements"),
          real_param("damping", 0.0, "1/s", at_least(0.0), "mass-proportional damping rate"),
          real_param("viscosity", 0.0, "Pa s", at_least(0.0),
                     "Kelvin-Voigt damping: a viscous stress eta dC/dt that leaves rigid "
                     "motion alone (explicit integrator only)"),
          string_param("integrator", std::string("explicit"),
                       "explicit (velocity Verlet, dt under the explicit limit) or "
                       "backward_euler (Newton-CG on the definite Hessian, any dt)",
                       {"explicit", "backward_euler"}),
          real_param("newton_tolerance", 1e-6, "1", above(0.0) & below(1.0),
                     "backward Euler: the gradient's reduction that ends Newton's loop"),
          int_param("newton_max_iterations", 50, at_least(1) & at_most(1000),
                    "backward Euler: Newton steps before the run stops as failed"),
          bool_param("volume_preserving", false,
                     "project positions and velocities onto constant one-ring volumes "
                     "after each step (Irving, Schroeder & Fedkiw 2007)"),
          real_param("volume_tolerance", 1e-8, "1", above(0.0) & below(1.0),
                     "volume_preserving: the per-node relative volume error allowed"),
          real_param("volume_recovery_time", 0.0, "s", at_least(0.0),
                     "volume_preserving: recover volume errors over this time by the "
                     "velocities alone; 0: correct the positions every step"),
          real_param("plastic_yield", 0.0, "1", at_least(0.0),
                     "multiplicative plasticity: the deviatoric Hencky strain (Frobenius "
                     "norm) beyond which elements flow; 0: elastic"),
          real_param("plastic_clamp", 3.0, "1", above(1.0),
                     "plasticity: F_p's stretches stay within [1/clamp, clamp]"),
          real_param("gravity", 0.0, "m/s^2", at_least(0.0), "gravity along -z"),
          real_param("floor", -1e30, "m", "height of the ground plane at x = y = 0"),
          real_param("floor_tilt", 0.0, "degrees", above(-90.0) & below(90.0),
                     "the ground's slope (a ramp down towards +x)"),
          real_param("friction", 0.0, "1", at_least(0.0),
                     "Coulomb friction coefficient of the ground and the plates (not with "
                     "volume_preserving)"),
          real_param("squash", 1.0, "1", above(-1.0) & at_most(1.0),
                     "initial z scale about the centre height (negative: mirrored, inverted)"),
          bool_param("pin_x0", false, "hold the x = min face fixed (a cantilever)"),
          real_param("plate_gap", 1.0, "1", above(0.0) & at_most(1.0),
                     "plates above and below close to this fraction of the body's height, "
                     "then open (1: no plates)"),
          real_param("plate_speed", 1.0, "m/s", above(0.0), "the speed of each plate"),
      }};
}

std::unique_ptr<Module> create(const Parameters& p, const Communicator& comm) {
  return std::make_unique<solid_module_detail::SolidModule>(p, comm);
}

}  // namespace amphora::physics::solid_fem
