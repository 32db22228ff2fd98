#include "physics/dem/dem_system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "kernels/grow_view.hpp"
#include "kernels/particles/binning.hpp"
#include "kernels/particles/pair_loop.hpp"
#include "physics/dem/dem_pair_law.hpp"

namespace amphora::physics::dem {

// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace dem_system_kernels {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// A periodic direction must be at least two cutoffs long: a particle then meets at most one
/// copy (itself or an image) of each partner, and never its own image.
void check_periodic_lengths(const DemConfig& c, double cutoff) {
  for (int d = 0; d < 3; ++d) {
    const double length = c.domain_hi[d] - c.domain_lo[d];
    if (c.periodic[d] && length < 2 * cutoff) {
      std::ostringstream m;
      m << "DEM: the domain is periodic along "
        << "xyz"[d] << " but " << length
        << " m long, shorter than two cutoffs (2 (2 max_radius + skin) = " << 2 * cutoff << " m)";
      throw std::invalid_argument(m.str());
    }
  }
}

}  // namespace dem_system_kernels
using namespace dem_system_kernels;
using kernels::particles::bin_points;
using kernels::particles::own_entry;
using kernels::particles::Rows3;

template <class ExecSpace>
DemSystem<ExecSpace>::DemSystem(const DemConfig& config, const Communicator& comm,
                                const ExecSpace& exec)
    : config_(config),
      comm_(comm),
      exec_(exec),
      decomposition_(config.domain_lo, config.domain_hi,
                     std::max(2 * config.max_radius + config.skin, config.min_halo_width), comm,
                     config.periodic, config.layout) {
  if (config_.materials.empty()) throw std::invalid_argument("DEM: no materials");
  if (!(config_.max_radius > 0)) throw std::invalid_argument("DEM: max_radius must be > 0");
  if (!(config_.skin > 0)) throw std::invalid_argument("DEM: skin must be > 0");
  if (!(config_.dt > 0)) throw std::invalid_argument("DEM: dt must be > 0");
  ghost_width_ = 2 * config_.max_radius + config_.skin;
  halo_width_ = std::max(ghost_width_, config_.min_halo_width);
  check_periodic_lengths(config_, halo_width_);
  const int nm = static_cast<int>(config_.materials.size());
  pairs_ = Kokkos::View<PairCoefficients**, Mem>("amphora::dem::pairs", nm, nm);
  auto ph = Kokkos::create_mirror_view(pairs_);
  for (int a = 0; a < nm; ++a)
    for (int b = 0; b < nm; ++b)
      ph(a, b) = pair_coefficients(config_.materials[a], config_.materials[b]);
  Kokkos::deep_copy(pairs_, ph);
  n_walls_ = static_cast<int>(config_.walls.size());
  if (n_walls_ > 32) throw std::invalid_argument("DEM: at most 32 walls (one bit each)");
  walls_ = Kokkos::View<Wall*, Mem>("amphora::dem::walls", n_walls_);
  auto wh = Kokkos::create_mirror_view(walls_);
  for (int w = 0; w < n_walls_; ++w) {
    wh(w) = config_.walls[w];
    if (wh(w).material < 0 || wh(w).material >= nm)
      throw std::invalid_argument("DEM: wall material out of range");
  }
  Kokkos::deep_copy(walls_, wh);
  x_build_ = Vec("amphora::dem::x_build", 0);
  wall_shear_ = Hist("amphora::dem::wall_shear", 0, std::max(n_walls_, 1));
  rec_shear_ = Hist("amphora::dem::rec_shear", 0, config_.max_contacts);
  rec_gid_ = RecIds("amphora::dem::rec_gid", 0, config_.max_contacts);
  shear_ = decltype(shear_)("amphora::dem::shear", 0);
  half_start_ = Kokkos::View<int*, Mem>("amphora::dem::half_start", 0);
  schedule_.order = Kokkos::View<int*, Mem>("amphora::dem::row_order", 0);
  schedule_.start = Kokkos::View<int*, Mem>("amphora::dem::slab_start", 1);
  list_.offsets = Kokkos::View<int*, Mem>("amphora::dem::list_offsets", 1);
  list_.neighbors = Kokkos::View<int*, Mem>("amphora::dem::list_neighbors", 0);
}

template <class ExecSpace>
void DemSystem<ExecSpace>::resize_owned(int n) {
  p_.reserve(n);
  kernels::grow_preserving(x_build_, n);
  kernels::grow_preserving(wall_shear_, n);
  kernels::grow_preserving(rec_shear_, n);
  kernels::grow_preserving(rec_gid_, n);
  if (external_.extent(0) > 0) kernels::grow_preserving(external_, n);
}

template <class ExecSpace>
typename DemSystem<ExecSpace>::Vec DemSystem<ExecSpace>::external_force() {
  if (external_.extent(0) == 0) {
    external_ = Vec("amphora::dem::external_force", std::max(1, p_.capacity()));
  }
  return external_;
}

template <class ExecSpace>
void DemSystem<ExecSpace>::clear_external_force(int first, int last) {
  if (external_.extent(0) == 0 || last <= first) return;
  Kokkos::deep_copy(exec_, Kokkos::subview(external_, Kokkos::make_pair(first, last), Kokkos::ALL),
                    0.0);
}

template <class ExecSpace>
void DemSystem<ExecSpace>::add_external_force() {
  if (external_.extent(0) == 0) return;
  const auto f = p_.force, e = external_;
  Kokkos::parallel_for(
      "amphora::dem::external_force", kernels::RangePolicy<ExecSpace>(exec_, 0, p_.n_owned),
      KOKKOS_LAMBDA(int i) {
        for (int d = 0; d < 3; ++d) f(i, d) += e(i, d);
      });
}

template <class ExecSpace>
void DemSystem<ExecSpace>::add_particles(const std::vector<ParticleSpec>& specs) {
  synchronize();
  std::vector<const ParticleSpec*> mine;
  for (const auto& s : specs) {
    if (!(s.radius > 0) || s.radius > config_.max_radius * (1 + 1e-12))
      throw std::invalid_argument("DEM: particle radius outside (0, max_radius]");
    if (s.material < 0 || s.material >= int(config_.materials.size()))
      throw std::invalid_argument("DEM: particle material out of range");
    for (int w = 0; w < n_walls_; ++w) {
      if (outside_wall(config_.walls[w], time_, s.x)) {
        std::ostringstream m;
        m << "particle " << s.gid << " at (" << s.x[0] << ", " << s.x[1] << ", " << s.x[2]
          << ") lies outside wall " << w;
        throw std::invalid_argument(m.str());
      }
    }
    if (decomposition_.owner(s.x) == comm_.rank()) mine.push_back(&s);
  }
  // Save the contact history first, while the partners' (ghosts included) ids are intact: the
  // new particles take the slots after the owned ones. Ghosts are rebuilt with the lists.
  history_to_records();
  p_.n_ghost = 0;
  const int n0 = p_.n_owned, n1 = n0 + static_cast<int>(mine.size());
  resize_owned(n1);
  clear_external_force(n0, n1);
  HostArrays h = to_host();
  auto &x = h.x, &v = h.v, &om = h.omega, &f = h.force, &tq = h.torque, &xb = h.x_build;
  auto &r = h.radius, &m = h.mass, &in = h.inertia;
  auto& mat = h.material;
  auto& gid = h.gid;
  auto& ws = h.wall_shear;
  auto& rg = h.rec_gid;
  for (int k = 0; k < int(mine.size()); ++k) {
    const ParticleSpec& s = *mine[k];
    const int i = n0 + k;
    for (int d = 0; d < 3; ++d) {
      x(i, d) = xb(i, d) = s.x[d];
      v(i, d) = s.v[d];
      om(i, d) = s.omega[d];
      f(i, d) = tq(i, d) = 0.0;
    }
    r(i) = s.radius;
    m(i) =
        config_.materials[s.material].density * 4.0 / 3.0 * M_PI * s.radius * s.radius * s.radius;
    in(i) = 0.4 * m(i) * s.radius * s.radius;
    mat(i) = s.material;
    gid(i) = s.gid;
    for (size_t w = 0; w < ws.extent(1); ++w)
      for (int d = 0; d < 3; ++d) ws(i, w, d) = 0.0;
    for (size_t c = 0; c < rg.extent(1); ++c) rg(i, c) = -1;
  }
  from_host(h);
  list_.n_rows = list_.n_entries = 0;  // no lists until the next rebuild (arrays kept)
  p_.n_owned = n1;
  need_rebuild_ = true;
  keep_build_positions_ = false;
  forces_valid_ = false;
}

template <class ExecSpace>
double DemSystem<ExecSpace>::timer_mark(double& slot, double since) const {
  if (!profiling_) return since;
  exec_.fence();
  const double t = now();
  slot += t - since;
  return t;
}

template <class ExecSpace>
void DemSystem<ExecSpace>::history_to_records() {
  // Collective on every path: ranks without particles (or lists) take part in the check.
  const bool have = has_lists() && p_.n_owned > 0;
  const int n = p_.n_owned;
  const int K = config_.max_contacts;
  const auto off = list_.offsets;
  const auto nbr = list_.neighbors;
  const auto half = half_start_;
  const kernels::particles::HalfPairList<Mem> pairs{off, nbr, half};
  const auto shear = shear_;
  const auto gid = p_.gid;
  const auto rg = rec_gid_;
  const auto rs = rec_shear_;
  int overflow = 0;
  Kokkos::parallel_reduce(
      "amphora::dem::history_to_records", kernels::RangePolicy<ExecSpace>(exec_, 0, have ? n : 0),
      KOKKOS_LAMBDA(int i, int& over) {
        // Both particles of a pair record its spring (in the pair's orientation): either may
        // be the one whose row evaluates it after the next rebuild.
        int r = 0;
        for (int k = off(i); k < off(i + 1); ++k) {
          const int j = nbr(k);
          const int e = k < half(i) ? own_entry(pairs, gid, j, gid(i)) : k;
          if (shear(e, 0) == 0.0 && shear(e, 1) == 0.0 && shear(e, 2) == 0.0) continue;
          if (r == K) {
            over = over > 0 ? over : 1;
            break;
          }
          rg(i, r) = gid(j);
          for (int d = 0; d < 3; ++d) rs(i, r, d) = shear(e, d);
          ++r;
        }
        for (; r < K; ++r) {  // empty slots are clean, so a checkpoint holds no stale bits
          rg(i, r) = -1;
          rs(i, r, 0) = rs(i, r, 1) = rs(i, r, 2) = 0.0;
        }
      },
      Kokkos::Max<int>(overflow));
  if (comm_.any(overflow > 0)) {
    throw std::runtime_error("DEM: a particle has more than max_contacts = " + std::to_string(K) +
                             " contacts with history; raise dem.max_contacts");
  }
}

template <class ExecSpace>
void DemSystem<ExecSpace>::clear_springs() {
  // The springs share the list's capacity (kept across rebuilds); its entries start at zero.
  const size_t capacity = list_.neighbors.extent(0);
  const auto label = [](const char* name) {
    return Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(name));
  };
  if (shear_.extent(0) < capacity)
    shear_ = decltype(shear_)(label("amphora::dem::shear"), capacity);
  size_next_springs();
  const auto a = shear_;
  const auto b = by_particle_ ? shear_next_ : shear_;
  Kokkos::parallel_for(
      "amphora::dem::clear_springs", kernels::RangePolicy<ExecSpace>(exec_, 0, list_.entries()),
      KOKKOS_LAMBDA(int k) {
        for (int d = 0; d < 3; ++d) a(k, d) = b(k, d) = 0.0;
      });
}

template <class ExecSpace>
void DemSystem<ExecSpace>::size_next_springs() {
  // Entries no row owns are never written by the by-particle loop, so a new array starts at 0.
  if (by_particle_ && shear_next_.extent(0) != shear_.extent(0))
    shear_next_ = decltype(shear_)("amphora::dem::shear_next", shear_.extent(0));
}

template <class ExecSpace>
void DemSystem<ExecSpace>::zero_forces() {
  const auto f = p_.force;
  const auto tq = p_.torque;
  Kokkos::parallel_for(
      "amphora::dem::zero_forces", kernels::RangePolicy<ExecSpace>(exec_, 0, int(f.extent(0))),
      KOKKOS_LAMBDA(int i) {
        for (int d = 0; d < 3; ++d) f(i, d) = tq(i, d) = 0.0;
      });
}

template <class ExecSpace>
void DemSystem<ExecSpace>::records_to_history() {
  const int n = p_.n_owned;
  const int K = config_.max_contacts;
  const auto off = list_.offsets;
  const auto nbr = list_.neighbors;
  clear_springs();
  const auto shear = shear_;
  const auto gid = p_.gid;
  const auto rg = rec_gid_;
  const auto rs = rec_shear_;
  const auto half = half_start_;
  const kernels::particles::HalfPairList<Mem> pairs{off, nbr, half};
  Kokkos::parallel_for(
      "amphora::dem::records_to_history", kernels::RangePolicy<ExecSpace>(exec_, 0, n),
      KOKKOS_LAMBDA(int i) {
        // Rows and records are both sorted by partner gid: merge. A spring goes to the row
        // that evaluates the pair: i's for larger-gid partners, a ghost partner's (which has
        // no records) for smaller-gid ghosts; an owned smaller-gid partner fills its own.
        int a = 0;
        for (int k = off(i); k < off(i + 1) && a < K; ++k) {
          const int j = nbr(k);
          const std::int64_t g = gid(j);
          if (k < half(i) && j < n) continue;
          while (a < K && rg(i, a) >= 0 && rg(i, a) < g) ++a;
          if (a < K && rg(i, a) == g) {
            const int e = k < half(i) ? own_entry(pairs, gid, j, gid(i)) : k;
            for (int d = 0; d < 3; ++d) shear(e, d) = rs(i, a, d);
          }
        }
      });
}

template <class ExecSpace>
void DemSystem<ExecSpace>::rebuild() {
  double t = profiling_ ? now() : 0.0;
  history_to_records();
  p_.n_ghost = 0;
  remove_and_migrate();
  t = timer_mark(timers_.comm, t);
  // Lists, ghosts and the rows' order follow the positions of this rebuild; a restart's first
  // rebuild keeps those of the checkpoint's (the run it continues built its lists there).
  if (!keep_build_positions_) {
    const int n_own = p_.n_owned;
    Kokkos::deep_copy(exec_, Kokkos::subview(x_build_, Kokkos::make_pair(0, n_own), Kokkos::ALL),
                      Kokkos::subview(p_.x, Kokkos::make_pair(0, n_own), Kokkos::ALL));
  }
  keep_build_positions_ = false;
  sort_owned_by_cell();
  t = timer_mark(timers_.binning, t);
  build_ghosts();
  t = timer_mark(timers_.comm, t);

  const int n = p_.n_owned, total = p_.size();
  const auto lo = decomposition_.lo(comm_.rank());
  const auto hi = decomposition_.hi(comm_.rank());
  double glo[3], ghi[3];
  for (int d = 0; d < 3; ++d) {  // the ghosts' reach (images beyond periodic faces)
    const bool per = config_.periodic[d];
    glo[d] = per ? lo[d] - halo_width_ : std::max(lo[d] - halo_width_, config_.domain_lo[d]);
    ghi[d] = per ? hi[d] + halo_width_ : std::min(hi[d] + halo_width_, config_.domain_hi[d]);
  }
  const CellGrid grid = CellGrid::covering(glo, ghi, ghost_width_);
  bin_points(exec_, grid, x_build_, total, kernels::particles::PointIndex(), bins_);
  t = timer_mark(timers_.binning, t);
  build_verlet_list(exec_, grid, bins_, x_build_, p_.radius, p_.gid, total, config_.skin, list_);
  kernels::particles::half_starts(exec_, list_, p_.gid, half_start_);
  records_to_history();
  schedule_current_ = false;
  if (!by_particle_) order_rows();  // a device's force loop runs by particle: no schedule
  {
    using kernels::grow_uninitialized;
    grow_uninitialized(wall_mask_, n, "amphora::dem::wall_mask");
    grow_uninitialized(wall_near_, n, "amphora::dem::wall_near");
    grow_uninitialized(row_mask_, total, "amphora::dem::row_mask");
    const auto mask = wall_mask_;
    const auto near = wall_near_;
    const auto rmask = row_mask_;
    const auto ws = wall_shear_;
    const auto sh = shear_;
    const auto off = list_.offsets;
    const auto half = half_start_;
    const auto x = x_build_;
    const auto rad = p_.radius;
    const auto walls = walls_;
    const int nw = n_walls_;
    const double t_now = time_, skin = config_.skin;
    Kokkos::parallel_for(
        "amphora::dem::history_masks", kernels::RangePolicy<ExecSpace>(exec_, 0, total),
        KOKKOS_LAMBDA(int i) {
          // Bit b: the spring of the row's b-th own entry (from half(i) on) may be set.
          unsigned r = 0;
          for (int k = half(i); k < off(i + 1) && k - half(i) < 32; ++k)
            if (sh(k, 0) != 0.0 || sh(k, 1) != 0.0 || sh(k, 2) != 0.0) r |= 1u << (k - half(i));
          rmask(i) = r;
          if (i >= n) return;  // ghosts: no walls here
          unsigned m = 0, w_near = 0;
          const double xi[3] = {x(i, 0), x(i, 1), x(i, 2)};
          for (int w = 0; w < nw; ++w) {
            if (ws(i, w, 0) != 0.0 || ws(i, w, 1) != 0.0 || ws(i, w, 2) != 0.0) m |= 1u << w;
            // Until the next rebuild a centre moves less than skin / 2, so a wall that stays
            // put and lies farther than r + skin cannot be touched; moving walls always can.
            const Wall& wall = walls(w);
            const bool moves =
                wall.velocity[0] != 0.0 || wall.velocity[1] != 0.0 || wall.velocity[2] != 0.0;
            double nn[3], delta, vw[3];
            if (moves || wall_contact(wall, t_now, xi, rad(i) + skin, nn, delta, vw))
              w_near |= 1u << w;
          }
          mask(i) = m;
          near(i) = w_near | m;
        });
  }
  timer_mark(timers_.list, t);
  ++timers_.rebuilds;
  need_rebuild_ = false;
}

template <class ExecSpace>
CellGrid DemSystem<ExecSpace>::row_cells() const {
  return CellGrid::covering(config_.domain_lo.data(), config_.domain_hi.data(), ghost_width_);
}

template <class ExecSpace>
void DemSystem<ExecSpace>::order_rows() {
  // Slabs of 2 cell layers, at least 2 ghost widths thick: rows of slabs two apart are more
  // than 4 r_max + skin apart at the build positions, so the particles they touch (within
  // 2 r_max, each centre within skin / 2 of its build position) are disjoint.
  kernels::particles::slab_schedule(exec_, row_cells(), x_build_, p_.size(), p_.gid, schedule_);
  schedule_current_ = true;
}

template <class ExecSpace>
double DemSystem<ExecSpace>::kick_drift() {
  const double dt = config_.dt;
  const auto x = p_.x, v = p_.v, om = p_.omega, f = p_.force, tq = p_.torque, xb = x_build_;
  const auto m = p_.mass, in = p_.inertia;
  const bool pending = pending_kick_;  // the last step's second half kick
  pending_kick_ = false;
  double max_d2 = 0.0;
  Kokkos::parallel_reduce(
      "amphora::dem::kick_drift", kernels::RangePolicy<ExecSpace>(exec_, 0, p_.n_owned),
      KOKKOS_LAMBDA(int i, double& acc) {
        const double hm = 0.5 * dt / m(i), hi = 0.5 * dt / in(i);
        double d2 = 0;
        for (int d = 0; d < 3; ++d) {
          const double fd = f(i, d), td = tq(i, d);
          double vd = v(i, d), wd = om(i, d);
          if (pending) {
            vd += hm * fd;
            wd += hi * td;
          }
          vd += hm * fd;
          wd += hi * td;
          const double xd = x(i, d) + dt * vd;
          v(i, d) = vd;
          om(i, d) = wd;
          x(i, d) = xd;
          const double dd = xd - xb(i, d);
          d2 += dd * dd;
          // used: the next force evaluation adds to zero (f is at hand here)
          f(i, d) = tq(i, d) = 0.0;
        }
        acc = kernels::math::max(acc, d2);
      },
      Kokkos::Max<double>(max_d2));
  forces_zeroed_ = true;
  return max_d2;
}

template <class ExecSpace>
void DemSystem<ExecSpace>::kick() const {
  const double dt = config_.dt;
  const auto v = p_.v, om = p_.omega, f = p_.force, tq = p_.torque;
  const auto m = p_.mass, in = p_.inertia;
  Kokkos::parallel_for(
      "amphora::dem::kick", kernels::RangePolicy<ExecSpace>(exec_, 0, p_.n_owned),
      KOKKOS_LAMBDA(int i) {
        const double hm = 0.5 * dt / m(i), hi = 0.5 * dt / in(i);
        for (int d = 0; d < 3; ++d) {
          v(i, d) += hm * f(i, d);
          om(i, d) += hi * tq(i, d);
        }
      });
}

template <class ExecSpace>
void DemSystem<ExecSpace>::compute_forces() {
  namespace particles = kernels::particles;
  const double g0 = config_.gravity[0], g1 = config_.gravity[1], g2 = config_.gravity[2];
  // Force and torque start at zero (kick_drift left them so, having used them): the slab
  // schedule's rows add to them (a row its particle's gravity, walls and share of its pairs
  // with larger-gid partners in one go, and the partners' shares to theirs).
  if (!forces_zeroed_) zero_forces();
  forces_zeroed_ = false;
  size_next_springs();
  // Restrict-qualified Views: no store through one may alias another, so the compiler keeps
  // loads in registers across the contact loop.
  const Rows3<const double> x(p_.x), v(p_.v), om(p_.omega);
  const Rows3<double> springs_out(by_particle_ ? shear_next_ : shear_);
  const HertzMindlinPairLaw<Mem> law{
      x,
      v,
      om,
      Rows3<double>(p_.force),
      Rows3<double>(p_.torque),
      Rows3<const double>(shear_),
      springs_out,
      p_.radius,
      p_.mass,
      p_.material,
      wall_near_,
      BodyForces<Mem>{p_.radius,
                      p_.mass,
                      p_.material,
                      pairs_,
                      walls_,
                      wall_shear_,
                      wall_mask_,
                      n_walls_,
                      config_.dt,
                      {g0, g1, g2}},
      PairContact<Mem>{v, om, p_.mass, p_.material, pairs_, config_.dt},
      time_};
  const particles::HalfPairList<Mem> pairs{list_.offsets, list_.neighbors, half_start_};
  const particles::Spheres<Mem> spheres{x, p_.radius};
  if (by_particle_) {
    particles::pair_sums_by_particle(exec_, pairs, spheres, p_.gid, p_.n_owned, p_.size(), law);
    std::swap(shear_, shear_next_);
  } else {
    if (!schedule_current_) order_rows();  // switched from by-particle since the last rebuild
    particles::pair_sums_by_slabs(exec_, schedule_, pairs, spheres, p_.n_owned, row_mask_, law);
  }
  add_external_force();
}

template <class ExecSpace>
void DemSystem<ExecSpace>::evaluate_forces_at_rest() {
  // A force evaluation advances the tangential springs; at an unchanged state they must not
  // move, so they are put back.
  decltype(shear_) springs("amphora::dem::shear_copy", shear_.extent(0));
  Hist wall_springs("amphora::dem::wall_shear_copy", wall_shear_.extent(0), wall_shear_.extent(1));
  Kokkos::View<unsigned*, Mem> masks("amphora::dem::row_mask_copy", row_mask_.extent(0));
  Kokkos::View<unsigned*, Mem> wall_masks("amphora::dem::wall_mask_copy", wall_mask_.extent(0));
  Kokkos::deep_copy(springs, shear_);
  Kokkos::deep_copy(wall_springs, wall_shear_);
  Kokkos::deep_copy(masks, row_mask_);
  Kokkos::deep_copy(wall_masks, wall_mask_);
  compute_forces();
  Kokkos::deep_copy(shear_, springs);
  Kokkos::deep_copy(wall_shear_, wall_springs);
  Kokkos::deep_copy(row_mask_, masks);
  Kokkos::deep_copy(wall_mask_, wall_masks);
  forces_valid_ = true;
}

template <class ExecSpace>
void DemSystem<ExecSpace>::redistribute() {
  // The forces travel with their particles (not evaluated anew: at the end of a step they are
  // those of the half-step velocities, and the deferred half kick still needs them).
  carry_forces_ = true;
  rebuild();
  carry_forces_ = false;
}

template <class ExecSpace>
void DemSystem<ExecSpace>::step() {
  double t = profiling_ ? now() : 0.0;
  if (!forces_valid_) {  // forces at the current state, for the first half kick
    if (need_rebuild_) rebuild();
    evaluate_forces_at_rest();
    t = timer_mark(timers_.force, t);
  }
  const double max_d2 = comm_.max(kick_drift());
  time_ = double(steps_ + 1) * config_.dt;
  ++steps_;
  t = timer_mark(timers_.integrate, t);
  const double half_skin = 0.5 * config_.skin;
  if (max_d2 > half_skin * half_skin) keep_build_positions_ = false;
  if (need_rebuild_ || max_d2 > half_skin * half_skin) {
    rebuild();
  } else {
    forward_ghosts();
  }
  t = timer_mark(timers_.comm, t);
  compute_forces();
  timer_mark(timers_.force, t);
  pending_kick_ = true;
}

template <class ExecSpace>
void DemSystem<ExecSpace>::set_wall_angular_velocity(int w, const double omega[3]) {
  for (int d = 0; d < 3; ++d) config_.walls[w].angular_velocity[d] = omega[d];
  auto wh = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), walls_);
  for (int d = 0; d < 3; ++d) wh(w).angular_velocity[d] = omega[d];
  Kokkos::deep_copy(walls_, wh);
}

AMPHORA_INSTANTIATE_ON_EXEC_SPACES(DemSystem)

}  // namespace amphora::physics::dem
