#include "physics/dem/dem_module.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace amphora::physics::dem {

ParamTable parameter_table() {
  return {
      "dem",
      "discrete elements: Hertz-Mindlin spheres in a box or a rotating drum",
      {
          string_param("geometry", std::string("box"), "box (settling bed) or drum",
                       {"box", "drum"}),
          real_param("box_x", 0.03, "m", above(0.0), "box width"),
          real_param("box_y", 0.03, "m", above(0.0), "box depth"),
          real_param("box_z", 0.06, "m", above(0.0), "box height (particles above it are removed)"),
          string_param("box_sides", std::string("walls"),
                       "the box's sides: walls, periodic along x and y (a slice of a wide bed), "
                       "or periodic_y (walls at x = 0 and box_x, periodic across y)",
                       {"walls", "periodic", "periodic_y"}),
          real_param("floor_height", 0.0, "m", at_least(0.0),
                     "height of the box's floor (below it: room for what a coupling needs, "
                     "e.g. CFD-DEM's inflow; a distributor the fluid passes)"),
          real_param("drum_radius", 0.04, "m", above(0.0), "drum inner radius"),
          real_param("drum_length", 0.012, "m", above(0.0),
                     "drum length (end caps turn with the drum)"),
          real_param("froude", 0.1, "1", above(0.0), "drum Froude number omega^2 R / g"),
          real_param("fill_level", 0.3, "1", above(0.0) & below(0.6),
                     "bed volume over drum volume (drum)"),
          real_param("settle_time", 0.2, "s", at_least(0.0),
                     "the drum starts turning after this time"),
          real_param("particle_radius", 1.5e-3, "m", above(0.0), "mean particle radius"),
          real_param("radius_spread", 0.0, "1", at_least(0.0) & below(1.0),
                     "radii uniform in r (1 -+ spread)"),
          real_param("density", 2500.0, "kg/m^3", above(0.0), "particle density (glass)"),
          real_param("youngs_modulus", 5e6, "Pa", above(0.0), "particle Young's modulus"),
          real_param("poisson_ratio", 0.3, "1", above(-1.0) & below(0.5),
                     "particle Poisson's ratio"),
          real_param("restitution", 0.9, "1", above(0.0) & at_most(1.0),
                     "particle-particle restitution coefficient"),
          real_param("friction", 0.5, "1", at_least(0.0), "sliding friction coefficient"),
          real_param("rolling_friction", 0.05, "1", at_least(0.0), "rolling friction coefficient"),
          real_param("cohesion_energy_density", 0.0, "J/m^3", at_least(0.0),
                     "SJKR cohesion (0: off)"),
          real_param("second_material_fraction", 0.0, "1", at_least(0.0) & at_most(1.0),
                     "share of particles of material 2"),
          real_param("second_density", 1050.0, "kg/m^3", above(0.0), "material 2 density (ABS)"),
          real_param("second_youngs_modulus", 5e6, "Pa", above(0.0), "material 2 Young's modulus"),
          real_param("wall_youngs_modulus", 5e6, "Pa", above(0.0), "wall Young's modulus"),
          real_param("wall_restitution", 0.9, "1", above(0.0) & at_most(1.0),
                     "wall restitution coefficient"),
          real_param("wall_friction", 0.5, "1", at_least(0.0), "wall friction coefficient"),
          string_param("insertion", std::string("random"), "random (over time) or lattice",
                       {"random", "lattice"}),
          int_param("particle_count", 2000, at_least(0),
                    "particles to insert (drum: 0 = from fill_level)"),
          real_param("insertion_rate", 10000.0, "1/s", at_least(0.0),
                     "random insertion rate (0: all at t = 0)"),
          real_param("insertion_velocity", 1.0, "m/s", at_least(0.0),
                     "downward speed of inserted particles"),
          int_param("insertion_attempts", 100, at_least(1),
                    "random draws per particle before giving up"),
          real_param("gravity", 9.81, "m/s^2", at_least(0.0),
                     "gravitational acceleration (-z box, -y drum)"),
          real_param("verlet_skin", 0.25, "1", above(0.0) & at_most(2.0),
                     "Verlet skin in largest diameters"),
          int_param("max_contacts", 24, at_least(6), "contact histories a particle may carry"),
          int_param("seed", 1, at_least(0), "seed of the insertion draws"),
          bool_param("allow_large_dt", false,
                     "accept a step over the Rayleigh/Hertz limit (at your risk)"),
      }};
}

DemModule::DemModule(const Parameters& p, const Communicator& comm, const DemSplit& split)
    : comm_(comm) {
  drum_ = p.string("geometry") == "drum";
  gravity_ = p.real("gravity");
  radii_ = {p.real("particle_radius"), p.real("radius_spread")};
  const double f2 = p.real("second_material_fraction");
  material_fractions_ = {1.0 - f2, f2};
  insertion_ = p.string("insertion");
  particle_count_ = p.integer("particle_count");
  insertion_rate_ = p.real("insertion_rate");
  insertion_velocity_ = p.real("insertion_velocity");
  insertion_attempts_ = static_cast<int>(p.integer("insertion_attempts"));
  seed_ = static_cast<std::uint64_t>(p.integer("seed"));
  allow_large_dt_ = p.boolean("allow_large_dt");

  Material m1, m2, wall;
  m1.density = p.real("density");
  m1.youngs_modulus = p.real("youngs_modulus");
  m1.poisson_ratio = p.real("poisson_ratio");
  m1.restitution = p.real("restitution");
  m1.friction = p.real("friction");
  m1.rolling_friction = p.real("rolling_friction");
  m1.cohesion_energy_density = p.real("cohesion_energy_density");
  m2 = m1;
  m2.density = p.real("second_density");
  m2.youngs_modulus = p.real("second_youngs_modulus");
  wall = m1;
  wall.youngs_modulus = p.real("wall_youngs_modulus");
  wall.restitution = p.real("wall_restitution");
  wall.friction = p.real("wall_friction");
  wall.cohesion_energy_density = 0;

  DemConfig c;
  c.materials = {m1, m2, wall};
  c.max_radius = radii_.max();
  c.skin = p.real("verlet_skin") * 2 * radii_.max();
  c.max_contacts = static_cast<int>(p.integer("max_contacts"));
  c.layout = split.layout;
  c.min_halo_width = split.min_halo_width;
  auto plane = [](int axis, double sign, double at) {
    Wall w;
    w.type = kPlane;
    w.axis[0] = w.axis[1] = w.axis[2] = 0;
    w.axis[axis] = sign;
    w.point[axis] = at;
    w.material = 2;
    return w;
  };
  if (!drum_) {
    box_[0] = p.real("box_x");
    box_[1] = p.real("box_y");
    box_[2] = p.real("box_z");
    c.gravity = {0, 0, -gravity_};
    c.domain_lo = {0, 0, 0};
    c.domain_hi = {box_[0], box_[1], box_[2]};
    floor_ = p.real("floor_height");
    if (floor_ >= 0.5 * box_[2])
      throw std::invalid_argument("dem: floor_height " + std::to_string(floor_) +
                                  " must lie below half the box's height " +
                                  std::to_string(box_[2]));
    const std::string sides = p.string("box_sides");
    c.periodic = {sides == "periodic", sides != "walls", false};
    c.walls = {plane(2, 1, floor_)};
    if (!c.periodic[0]) c.walls.insert(c.walls.end(), {plane(0, 1, 0), plane(0, -1, box_[0])});
    if (!c.periodic[1]) c.walls.insert(c.walls.end(), {plane(1, 1, 0), plane(1, -1, box_[1])});
    impact_speed_ = std::sqrt(2 * gravity_ * box_[2]);
  } else {
    drum_radius_ = p.real("drum_radius");
    drum_length_ = p.real("drum_length");
    drum_omega_ = std::sqrt(p.real("froude") * gravity_ / drum_radius_);
    settle_time_ = p.real("settle_time");
    if (drum_radius_ < 5 * radii_.max() || drum_length_ < 2.2 * radii_.max())
      throw std::invalid_argument(
          "dem: the drum must be at least 5 particle radii wide and 2.2 long");
    c.gravity = {0, -gravity_, 0};
    c.domain_lo = {-drum_radius_, -drum_radius_, 0};
    c.domain_hi = {drum_radius_, drum_radius_, drum_length_};
    Wall cyl;
    cyl.type = kCylinder;
    cyl.radius = drum_radius_;
    cyl.length = drum_length_;
    cyl.material = 2;
    c.walls = {cyl, plane(2, 1, 0), plane(2, -1, drum_length_)};
    impact_speed_ = std::max(drum_omega_ * drum_radius_, std::sqrt(4 * gravity_ * drum_radius_));
  }

  // Stability: 20% of the Rayleigh time and 10% of the Hertz contact time at the largest
  // expected impact speed, for the smallest and softest particle (LIGGGHTS' guidance).
  const double r_min = radii_.mean * (1 - radii_.spread);
  rayleigh_ = std::min(rayleigh_time(m1, r_min), f2 > 0 ? rayleigh_time(m2, r_min) : 1e300);
  hertz_ = 1e300;
  for (const Material* a : {&m1, &m2}) {
    if (a == &m2 && f2 == 0) continue;
    const double mass = a->density * 4.0 / 3.0 * M_PI * r_min * r_min * r_min;
    const PairCoefficients pc = pair_coefficients(*a, *a);
    hertz_ =
        std::min(hertz_, hertz_contact_time(0.5 * mass, 0.5 * r_min, pc.e_star, impact_speed_));
  }
  dt_limit_ = std::min(0.2 * rayleigh_, 0.1 * hertz_);
  c.dt = dt_limit_;
  system_ = std::make_unique<System>(c, comm_);

  // What insertion can never satisfy is an error now, before anything runs.
  if (drum_) {
    const double v_drum = M_PI * drum_radius_ * drum_radius_ * drum_length_;
    const double v_particle = 4.0 / 3.0 * M_PI * std::pow(radii_.mean, 3);
    if (particle_count_ == 0)
      particle_count_ = std::llround(0.6 * p.real("fill_level") * v_drum / v_particle);
    insertion_ = "lattice";
  }
  if (insertion_ == "random") {
    const double region = box_[0] * box_[1] * 0.5 * box_[2];
    const double batch =
        insertion_rate_ > 0
            ? std::min<double>(particle_count_, insertion_rate_ * insertion_interval_)
            : double(particle_count_);
    const double solid = batch * 4.0 / 3.0 * M_PI * std::pow(radii_.max(), 3);
    if (solid > 0.3 * region) {
      std::ostringstream m;
      m << "dem: random insertion cannot fit " << batch << " particles per event in the upper "
        << "half of the box (solid fraction " << solid / region << " > 0.3); lower "
        << "dem.insertion_rate or dem.particle_count, or enlarge the box";
      throw std::invalid_argument(m.str());
    }
  }
  insert_due(0.0);
}

void DemModule::set_time_step(double dt) {
  if (dt > dt_limit_ * (1 + 1e-12) && !allow_large_dt_) {
    std::ostringstream m;
    m << "time step " << dt << " s exceeds the DEM stability limit " << dt_limit_
      << " s = min(0.2 x Rayleigh time " << rayleigh_ << " s, 0.1 x Hertz contact time " << hertz_
      << " s at " << impact_speed_ << " m/s); lower run.dt or set "
      << "dem.allow_large_dt = true";
    throw std::invalid_argument(m.str());
  }
  system_->set_dt(dt);
}

void DemModule::insert_due(double t) {
  if (inserted_ >= particle_count_) return;
  std::vector<ParticleSpec> batch;
  if (insertion_ == "lattice") {
    if (next_event_ > 0) return;
    InsertionRegion region;
    const double spacing = 2 * radii_.max() * 1.05;
    if (drum_) {
      region.kind = InsertionRegion::kCylinder;
      region.lo[0] = region.lo[1] = -drum_radius_;
      region.hi[0] = region.hi[1] = drum_radius_;
      region.hi[2] = drum_length_;
      region.radius = drum_radius_;
      auto all = lattice_insertion(region, radii_, spacing, 0, 0.02 * radii_.mean, seed_, 0,
                                   material_fractions_);
      // Fill from the bottom up.
      std::stable_sort(all.begin(), all.end(), [](const ParticleSpec& a, const ParticleSpec& b) {
        return a.x[1] < b.x[1];
      });
      if ((long long)all.size() < particle_count_) {
        std::ostringstream m;
        m << "dem: lattice insertion cannot fit " << particle_count_ << " particles in the drum ("
          << all.size() << " sites); lower dem.fill_level or dem.particle_count";
        throw InsertionError(m.str());
      }
      all.resize(static_cast<size_t>(particle_count_));
      for (size_t k = 0; k < all.size(); ++k) all[k].gid = static_cast<std::int64_t>(k);
      batch = std::move(all);
    } else {
      region.lo[2] = floor_;
      region.hi[0] = box_[0];
      region.hi[1] = box_[1];
      region.hi[2] = box_[2];
      batch = lattice_insertion(region, radii_, spacing, particle_count_, 0.02 * radii_.mean, seed_,
                                0, material_fractions_, system_->config().periodic);
    }
    next_event_ = 1;
  } else {
    const double event_time = double(next_event_) * insertion_interval_;
    if (t + 1e-12 < event_time) return;
    InsertionRegion region;
    region.lo[2] = 0.5 * box_[2];
    region.hi[0] = box_[0];
    region.hi[1] = box_[1];
    region.hi[2] = box_[2];
    long long n =
        insertion_rate_ > 0 ? std::llround(insertion_rate_ * insertion_interval_) : particle_count_;
    n = std::max(1LL, std::min(n, particle_count_ - inserted_));
    batch =
        random_insertion(*system_, region, radii_, n, insertion_attempts_, seed_,
                         static_cast<std::uint64_t>(next_event_), inserted_, material_fractions_);
    for (auto& q : batch) q.v[2] = -insertion_velocity_;
    ++next_event_;
  }
  inserted_ += static_cast<long long>(batch.size());
  system_->add_particles(batch);
}

void DemModule::update_drum(double t) {
  if (!drum_ || drum_turning_ || t + 1e-12 < settle_time_) return;
  const double w[3] = {0, 0, drum_omega_};
  for (int k = 0; k < 3; ++k) system_->set_wall_angular_velocity(k, w);
  drum_turning_ = true;
}

void DemModule::advance(double t, double /*dt*/) {
  insert_due(t);
  update_drum(t);
  system_->step();
}

long long DemModule::work_per_step() const { return std::max(1LL, system_->global_count()); }

DemModule::System::HostState DemModule::gather() const {
  const System::HostState mine = system_->save();
  System::HostState all;
  all.x = comm_.gatherv(mine.x);
  all.x_build = comm_.gatherv(mine.x_build);
  all.v = comm_.gatherv(mine.v);
  all.omega = comm_.gatherv(mine.omega);
  all.force = comm_.gatherv(mine.force);
  all.torque = comm_.gatherv(mine.torque);
  all.radius = comm_.gatherv(mine.radius);
  all.wall_shear = comm_.gatherv(mine.wall_shear);
  all.contact_shear = comm_.gatherv(mine.contact_shear);
  all.gid = comm_.gatherv(mine.gid);
  all.contact_gid = comm_.gatherv(mine.contact_gid);
  all.material = comm_.gatherv(mine.material);
  if (!comm_.is_root()) return all;
  // Sort by gid so the files do not depend on the rank count.
  const size_t n = all.gid.size();
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return all.gid[a] < all.gid[b]; });
  // Per-particle widths: wall history (3 per wall), contact records (gid, and 3 of history).
  const size_t nw = n ? all.wall_shear.size() / n : 0, nk = n ? all.contact_gid.size() / n : 0;
  System::HostState s;
  for (size_t i : order) {
    auto put = [&](const auto& src, auto& dst, size_t width) {
      dst.insert(dst.end(), src.begin() + i * width, src.begin() + (i + 1) * width);
    };
    put(all.x, s.x, 3);
    put(all.x_build, s.x_build, 3);
    put(all.v, s.v, 3);
    put(all.omega, s.omega, 3);
    put(all.force, s.force, 3);
    put(all.torque, s.torque, 3);
    put(all.radius, s.radius, 1);
    put(all.material, s.material, 1);
    put(all.gid, s.gid, 1);
    put(all.wall_shear, s.wall_shear, nw);
    put(all.contact_gid, s.contact_gid, nk);
    put(all.contact_shear, s.contact_shear, 3 * nk);
  }
  return s;
}

std::vector<OutputBlock> DemModule::output(double) const {
  const System::HostState s = gather();
  if (!comm_.is_root()) return {};
  OutputBlock b;
  b.name = "particles";
  b.points = true;
  const size_t n = s.radius.size();
  std::vector<double> vx(n), vy(n), vz(n), speed(n), spin(n), gid(n), mat(n);
  for (size_t i = 0; i < n; ++i) {
    b.x.push_back(s.x[3 * i]);
    b.y.push_back(s.x[3 * i + 1]);
    b.z.push_back(s.x[3 * i + 2]);
    vx[i] = s.v[3 * i];
    vy[i] = s.v[3 * i + 1];
    vz[i] = s.v[3 * i + 2];
    speed[i] = std::sqrt(vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]);
    spin[i] = std::sqrt(s.omega[3 * i] * s.omega[3 * i] + s.omega[3 * i + 1] * s.omega[3 * i + 1] +
                        s.omega[3 * i + 2] * s.omega[3 * i + 2]);
    gid[i] = double(s.gid[i]);
    mat[i] = s.material[i];
  }
  b.fields = {{"radius", s.radius}, {"gid", gid}, {"material", mat}, {"vx", vx},
              {"vy", vy},           {"vz", vz},   {"speed", speed},  {"spin", spin}};
  return {b};
}

DrumClassification DemModule::drum_regime() const {
  const auto& p = system_->particles();
  auto x = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.x);
  auto v = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.v);
  const std::vector<int> contacts = system_->contact_counts();
  std::vector<double> xs, vs;
  for (int i = 0; i < p.n_owned; ++i)
    for (int d = 0; d < 3; ++d) {
      xs.push_back(x(i, d));
      vs.push_back(v(i, d));
    }
  // Gather to rank 0, classify there, broadcast the result.
  const std::vector<double> ax = comm_.gatherv(xs), av = comm_.gatherv(vs);
  const std::vector<int> ac = comm_.gatherv(contacts);
  DrumClassification c;
  double buf[5] = {0, 0, 0, 0, 0};
  if (comm_.is_root()) {
    DrumState d{drum_radius_, drum_turning_ ? drum_omega_ : 0.0, 2 * radii_.mean};
    c = classify_drum(d, ax, av, ac);
    buf[0] = double(static_cast<int>(c.regime));
    buf[1] = c.upper_fraction;
    buf[2] = c.airborne_fraction;
    buf[3] = c.surface_angle;
    buf[4] = c.surface_deviation;
  }
  MPI_Bcast(buf, 5, MPI_DOUBLE, 0, comm_.get());
  c.regime = static_cast<DrumRegime>(static_cast<int>(buf[0]));
  c.upper_fraction = buf[1];
  c.airborne_fraction = buf[2];
  c.surface_angle = buf[3];
  c.surface_deviation = buf[4];
  return c;
}

Diagnostics DemModule::diagnostics(double t) const {
  const DemDiagnostics d = system_->diagnostics();
  Diagnostics out = {{"particles", double(d.particles)},         {"contacts", double(d.contacts)},
                     {"wall_contacts", double(d.wall_contacts)}, {"kinetic_energy", d.kinetic},
                     {"rotational_energy", d.rotational},        {"max_overlap", d.max_overlap}};
  if (drum_) {
    const DrumClassification c = drum_regime();
    // Average once the drum has turned a quarter revolution (and at least 0.3 s): the regime
    // is a property of the steady motion, not of one snapshot.
    const double steady = settle_time_ + std::max(0.3, 0.5 * M_PI / drum_omega_);
    if (drum_turning_ && t >= steady) {
      regime_sums_[0] += 1;
      regime_sums_[1] += c.upper_fraction;
      regime_sums_[2] += c.airborne_fraction;
      regime_sums_[3] += c.surface_angle;
      regime_sums_[4] += c.surface_deviation;
    }
    const double n = regime_sums_[0];
    const double upper = n > 0 ? regime_sums_[1] / n : c.upper_fraction;
    const double airborne = n > 0 ? regime_sums_[2] / n : c.airborne_fraction;
    const double angle = n > 0 ? regime_sums_[3] / n : c.surface_angle;
    const double deviation = n > 0 ? regime_sums_[4] / n : c.surface_deviation;
    out.emplace_back("froude", drum_omega_ * drum_omega_ * drum_radius_ / gravity_);
    out.emplace_back("regime", double(static_cast<int>(regime_of(upper, airborne, deviation))));
    out.emplace_back("regime_samples", n);
    out.emplace_back("upper_fraction", upper);
    out.emplace_back("airborne_fraction", airborne);
    out.emplace_back("surface_angle", angle);
    out.emplace_back("surface_deviation", deviation);
  }
  return out;
}

std::optional<NonFiniteReport> DemModule::find_nonfinite() const {
  const std::int64_t bad = system_->first_nonfinite();
  if (bad < 0) return std::nullopt;
  NonFiniteReport r;
  r.field = "position/velocity";
  r.block = "particles";
  r.index = bad;
  return r;
}

std::vector<std::string> DemModule::owned_blocks() const {
  return comm_.is_root() ? std::vector<std::string>{"particles"} : std::vector<std::string>{};
}

std::vector<StateBlock> DemModule::state() const {
  const System::HostState s = gather();
  if (!comm_.is_root()) return {};
  auto as_double = [](const auto& v) { return std::vector<double>(v.begin(), v.end()); };
  StateBlock b;
  b.name = "particles";
  b.arrays = {{"x", s.x},
              {"v", s.v},
              {"omega", s.omega},
              {"force", s.force},
              {"torque", s.torque},
              {"x_build", s.x_build},
              {"radius", s.radius},
              {"material", as_double(s.material)},
              {"gid", as_double(s.gid)},
              {"wall_shear", s.wall_shear},
              {"contact_gid", as_double(s.contact_gid)},
              {"contact_shear", s.contact_shear},
              {"module",
               {double(inserted_), double(next_event_), system_->time(), double(system_->steps()),
                drum_turning_ ? 1.0 : 0.0, regime_sums_[0], regime_sums_[1], regime_sums_[2],
                regime_sums_[3], regime_sums_[4]}}};
  return {b};
}

void DemModule::restore(const std::vector<StateBlock>& blocks) {
  // Rank 0 read the checkpoint; every rank gets it and keeps the particles it owns.
  std::map<std::string, std::vector<double>> arrays;
  if (comm_.is_root()) {
    if (blocks.empty()) throw std::runtime_error("checkpoint lacks block 'particles'");
    for (const auto& [name, data] : blocks[0].arrays) arrays[name] = data;
  }
  // x_build: absent from checkpoints of before it was kept (they continue from their x)
  for (const char* name : {"x", "x_build", "v", "omega", "force", "torque", "radius", "material",
                           "gid", "wall_shear", "contact_gid", "contact_shear", "module"}) {
    std::vector<double>& a = arrays[name];
    long long n = static_cast<long long>(a.size());
    MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, comm_.get());
    a.resize(static_cast<size_t>(n));
    MPI_Bcast(a.data(), static_cast<int>(n), MPI_DOUBLE, 0, comm_.get());
  }
  System::HostState s;
  s.x = arrays["x"];
  s.x_build = arrays["x_build"];
  s.v = arrays["v"];
  s.omega = arrays["omega"];
  s.force = arrays["force"];
  s.torque = arrays["torque"];
  s.radius = arrays["radius"];
  s.wall_shear = arrays["wall_shear"];
  s.contact_shear = arrays["contact_shear"];
  for (double m : arrays["material"]) s.material.push_back(static_cast<int>(m));
  for (double g : arrays["gid"]) s.gid.push_back(static_cast<std::int64_t>(g));
  for (double g : arrays["contact_gid"]) s.contact_gid.push_back(static_cast<std::int64_t>(g));
  const std::vector<double>& mod = arrays["module"];
  if (mod.size() != 10) throw std::runtime_error("checkpoint: malformed DEM module state");
  for (int k = 0; k < 5; ++k) regime_sums_[k] = mod[5 + k];
  inserted_ = static_cast<long long>(mod[0]);
  next_event_ = static_cast<long long>(mod[1]);
  system_->set_clock(mod[2], static_cast<long long>(mod[3]));
  if (mod[4] != 0.0) {
    drum_turning_ = false;
    update_drum(1e300);
  }
  system_->load(s);
}

}  // namespace amphora::physics::dem
