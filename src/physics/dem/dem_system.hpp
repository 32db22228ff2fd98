#pragma once
// The DEM solver: particles with Hertz–Mindlin contacts among themselves and with walls,
// gravity, velocity-Verlet integration of translation and rotation (LIGGGHTS' nve/sphere
// splitting), binned contact detection with Verlet lists rebuilt only when the largest
// displacement since the last build could close half the skin, and spatial decomposition over
// MPI ranks with ghost particles and migration. Tangential history lives with the list between
// rebuilds and with the particles across them (records keyed by the partner's global id), so it
// survives rebuilds, sorting and migration.
//
// Each pair's contact law is evaluated once, in the pair's own orientation (smaller global id
// first), by the row of its first particle, which keeps the spring, takes its share and adds
// the partner's to the partner's force (ghosts have rows too: a ghost's row evaluates its pairs
// with owned particles). Rows run in slabs across z, each two cutoffs (2 r_max + skin) thick
// or more, so rows of every other slab reach disjoint particles and those slabs run in
// parallel; each slab's rows run in a fixed order (global cell, then gid, at the positions of
// the last rebuild). A particle thus receives its contributions in an order set by the
// particles alone: trajectories are the same bits on any thread or rank count, and a
// checkpoint (which carries the positions of the last rebuild) continues bit for bit. On
// devices, where the slabs are too few to fill the device, one work item per particle sums the
// forces on its particle from all its pairs instead (forces_by_particle): each pair is evaluated
// by both particles, in the orientation of the smaller gid, so both see the same bits and no
// atomics are needed; the sums are again in an order set by the particles alone.
#include <array>
#include <cstdint>
#include <vector>

#include "base/communicator.hpp"
#include "kernels/particles/slab_schedule.hpp"
#include "kernels/particles/verlet_list.hpp"
#include "mesh/particles/particle_fields.hpp"
#include "mesh/particles/particle_halo.hpp"
#include "mesh/particles/particle_migration.hpp"
#include "mesh/particles/particle_set.hpp"
#include "mesh/particles/spatial_decomposition.hpp"
#include "physics/dem/contact_model.hpp"
#include "physics/dem/walls.hpp"

namespace amphora::physics::dem {

using kernels::particles::CellGrid;
using kernels::particles::NeighborList;
using mesh::particles::ParticleSet;

struct DemConfig {
  std::vector<Material> materials;  ///< particle and wall materials, indexed by material id
  std::vector<Wall> walls;
  std::array<double, 3> gravity{0.0, 0.0, -9.81};
  std::array<double, 3> domain_lo{0, 0, 0}, domain_hi{1, 1, 1};  ///< particles leaving are removed
  /// Directions in which the domain is periodic: particles leaving re-enter at the opposite
  /// face and meet the images of those there (the domain at least two cutoffs long).
  std::array<bool, 3> periodic{false, false, false};
  double dt = 1e-5;
  double skin = 0;        ///< Verlet skin [m]
  double max_radius = 0;  ///< largest radius the run will hold (bins, ghost width)
  int max_contacts = 24;  ///< history records a particle carries across a rebuild
  /// The subdomains as whole blocks of a coupling's grid (default: cells of the ghost width).
  mesh::particles::DecompositionLayout layout;
  /// Ghosts reach at least this far from a subdomain (a coupling that reads the neighbours'
  /// particles, e.g. QCM's reference spheres); the contact cutoff 2 max_radius + skin at least.
  double min_halo_width = 0;
};

/// One particle to add (host side).
struct ParticleSpec {
  double x[3] = {0, 0, 0}, v[3] = {0, 0, 0}, omega[3] = {0, 0, 0};
  double radius = 0;
  int material = 0;
  std::int64_t gid = 0;
};

struct DemDiagnostics {
  long long particles = 0, contacts = 0, wall_contacts = 0;
  double kinetic = 0, rotational = 0, gravity_potential = 0, elastic = 0;
  double max_overlap = 0;  ///< largest overlap / smaller radius over all contacts
  double total_energy() const { return kinetic + rotational + gravity_potential + elastic; }
};

/// Wall-clock seconds per phase (measured only when profiling is on: it fences each phase).
struct DemTimers {
  double integrate = 0, binning = 0, list = 0, force = 0, comm = 0;
  long long rebuilds = 0;
};

template <class ExecSpace>
class DemSystem {
 public:
  using Mem = typename ExecSpace::memory_space;
  using Vec = typename ParticleSet<Mem>::Vec;
  using Hist = Kokkos::View<double** [3], Kokkos::LayoutRight, Mem>;
  using RecIds = Kokkos::View<std::int64_t**, Kokkos::LayoutRight, Mem>;

  DemSystem(const DemConfig& config, const Communicator& comm, const ExecSpace& exec = ExecSpace());

  /// Adds the particles of `specs` that lie in this rank's subdomain (every rank may pass the
  /// same list). Throws if a particle's centre lies outside a wall.
  void add_particles(const std::vector<ParticleSpec>& specs);
  /// One velocity-Verlet step of length dt. Collective.
  void step();

  double time() const { return time_; }
  void set_time(double t) { time_ = t; }
  /// Time and step count, as a checkpoint saved them.
  void set_clock(double t, long long steps) {
    time_ = t;
    steps_ = steps;
  }
  long long steps() const { return steps_; }
  const DemConfig& config() const { return config_; }
  void set_dt(double dt) { config_.dt = dt; }
  const mesh::particles::SpatialDecomposition& decomposition() const { return decomposition_; }
  ParticleSet<Mem>& particles() {
    synchronize();
    return p_;
  }
  const ParticleSet<Mem>& particles() const {
    synchronize();
    return p_;
  }
  const NeighborList<Mem>& neighbor_list() const { return list_; }
  long long global_count() const { return comm_.sum(static_cast<long long>(p_.n_owned)); }

  /// Pairs (gid_i < gid_j) of owned i now in contact (centre distance < r_i + r_j), as the
  /// force kernel sees them through the Verlet list.
  std::vector<std::pair<std::int64_t, std::int64_t>> contact_pairs() const;
  DemDiagnostics diagnostics() const;  ///< collective
  void set_profiling(bool on) { profiling_ = on; }
  const DemTimers& timers() const { return timers_; }
  /// The pair forces one work item per particle (each pair evaluated by both, as on devices, the
  /// default there) instead of slabs of rows in two colours (the default on host spaces). The
  /// same forces up to round-off: the sums run in another order.
  void set_forces_by_particle(bool on) { by_particle_ = on; }
  /// Forces a neighbour-list rebuild (and migration) before the next force evaluation.
  void invalidate() { need_rebuild_ = true; }
  /// Migrates every particle to the rank whose subdomain holds it and rebuilds the lists and
  /// ghosts now (between steps: a coupling that needs each particle on its owner), the forces
  /// and the deferred half kick carried along: the trajectories are unchanged. Collective.
  void redistribute();
  /// How far the ghosts reach from this rank's subdomain.
  double halo_width() const { return halo_width_; }
  /// The rows' positions (owned and ghosts) at the last list build: owned ones inside the box
  /// along periodic directions, periodic images outside it (positions now may have drifted
  /// past a face since).
  const Vec& build_positions() const { return x_build_; }
  /// Force on each owned particle from outside the DEM (a coupling's fluid force), added to
  /// every force evaluation until changed; it travels with its particle through sorting and
  /// migration, and new or loaded particles start with none. The first call allocates it
  /// (zero). Rows [0, particles().n_owned) are the owned particles in storage order.
  Vec external_force();
  /// Sets the rigid rotation of wall w (e.g. a drum starting to turn).
  void set_wall_angular_velocity(int w, const double omega[3]);
  /// Contacts (particles and walls) of each owned particle, in storage order (host).
  std::vector<int> contact_counts() const;
  /// Global id of an owned particle whose position or velocity is not finite, or -1; the
  /// smallest such gid over all ranks. Collective.
  std::int64_t first_nonfinite() const;

  /// Per-particle records for a checkpoint (owned particles, host): x, v, omega, force,
  /// torque, radius, material, gid, wall history, contact records (partner gid, history).
  struct HostState {
    std::vector<double> x, v, omega, force, torque, radius, wall_shear, contact_shear;
    std::vector<double> x_build;  ///< positions at the last rebuild (empty: x)
    std::vector<std::int64_t> gid, contact_gid;
    std::vector<int> material;
  };
  HostState save() const;
  /// Replaces all particles with those of `s` that lie in this rank's subdomain.
  void load(const HostState& s);

 public:  // (CUDA: extended lambdas may not live in private member functions)
  /// Host copies of every per-particle array (mirrors: no copy at all on a host backend).
  struct HostArrays {
    kernels::host_mirror_t<Vec> x, v, omega, force, torque, x_build;
    kernels::host_mirror_t<typename ParticleSet<Mem>::Scalar> radius, mass, inertia;
    kernels::host_mirror_t<typename ParticleSet<Mem>::Int> material;
    kernels::host_mirror_t<typename ParticleSet<Mem>::Id> gid;
    kernels::host_mirror_t<Hist> wall_shear, rec_shear;
    kernels::host_mirror_t<RecIds> rec_gid;
  };
  HostArrays to_host() const;
  void from_host(const HostArrays& h);

  void rebuild();
  /// Whether the lists are those of the current particles (rows for owned and ghosts): not
  /// so between an insertion or a load and the next rebuild.
  bool has_lists() const { return list_.rows() == p_.size(); }
  void history_to_records();
  void records_to_history();
  /// The springs grown to the Verlet list's capacity and zeroed on its entries.
  void clear_springs();
  /// shear_next_ (the by-particle loop's output springs) sized as shear_, zero where new.
  void size_next_springs();
  void zero_forces();  // force and torque to zero, in one kernel
  /// The forces of the current state with the springs put back (an evaluation advances them).
  void evaluate_forces_at_rest();
  void remove_and_migrate();
  void wrap_periodic();  // owned positions into the domain along its periodic directions
  /// Every per-particle array a particle carries to another rank.
  mesh::particles::ParticleFields<ExecSpace> migrating_fields() const;
  void sort_owned_by_cell();
  void build_ghosts();
  void forward_ghosts();
  /// Forces and torques of the current state: the pair loops of kernels/particles with the
  /// Hertz–Mindlin pair law (dem_pair_law.hpp), by slabs (host spaces) or by particle
  /// (devices: each pair evaluated by both of its particles, the springs read from shear_ and
  /// written to shear_next_, then swapped).
  void compute_forces();
  void order_rows();
  CellGrid row_cells() const;  // the domain's grid the rows' order is taken on
  double kick_drift();
  // A step's second half kick is deferred to the next step's first (one pass over the
  // particles instead of two; the same two additions, so the same bits): until then the
  // velocities are half a step behind, and every reader of them calls synchronize() first.
  void kick() const;
  void synchronize() const {
    if (!pending_kick_) return;
    kick();
    pending_kick_ = false;
  }
  void resize_owned(int n);
  void clear_external_force(int first, int last);  // rows [first, last) to zero
  void add_external_force();                       // force += external force (owned)
  double timer_mark(double& slot, double since) const;

 private:
  DemConfig config_;
  Communicator comm_;
  ExecSpace exec_;
  mesh::particles::SpatialDecomposition decomposition_;
  Kokkos::View<PairCoefficients**, Mem> pairs_;
  Kokkos::View<Wall*, Mem> walls_;
  int n_walls_ = 0;
  double ghost_width_ = 0;  // the contact cutoff: 2 max_radius + skin
  double halo_width_ = 0;   // the ghosts' reach: ghost_width_ or config.min_halo_width

  ParticleSet<Mem> p_;
  Vec external_;  // external force per owned particle; empty: none
  // Positions at the last rebuild (owned and ghosts): the lists, the ghosts and the rows' order
  // are those of these positions.
  Vec x_build_;
  bool carry_forces_ = false;          // migration carries force and torque (redistribute)
  bool keep_build_positions_ = false;  // the next rebuild keeps x_build_ (a restart's first)
  bool forces_zeroed_ = false;         // force and torque are zero, ready for a force evaluation
  Hist wall_shear_;                    // (particle, wall, 3)
  // Bit w set: wall w's history of this particle may be non-zero. Derived from wall_shear_
  // at each rebuild, so the force loop reads a particle's wall histories only when it must.
  Kokkos::View<unsigned*, Mem> wall_mask_;
  // Bit w set: wall w may touch the particle before the next rebuild (set at each rebuild).
  Kokkos::View<unsigned*, Mem> wall_near_;
  // Bit b set: entry half_start_(i) + b of row i (its b-th own pair) may hold a non-zero
  // spring (rows with more than 32 own pairs keep their tail entries always "set"). Spares
  // the force loop the history reads of the many listed neighbours that do not touch.
  Kokkos::View<unsigned*, Mem> row_mask_;
  Hist rec_shear_;          // (particle, record, 3), valid across a rebuild
  RecIds rec_gid_;          // (particle, record): partner gid or -1
  NeighborList<Mem> list_;  // rows for owned particles and ghosts
  // Aligned with list_.neighbors: the springs of the pairs each row evaluates (zero elsewhere).
  Kokkos::View<double* [3], Kokkos::LayoutRight, Mem> shear_;
  // forces_by_particle's springs of the next step (swapped with shear_ after each evaluation)
  Kokkos::View<double* [3], Kokkos::LayoutRight, Mem> shear_next_;
  bool by_particle_ = !kernels::runs_on_host_v<ExecSpace>;
  // Row i's entries from half_start_(i) on are its partners of larger gid: the pairs it
  // evaluates.
  Kokkos::View<int*, Mem> half_start_;
  // Rows in the order they run: slab by slab (slabs of one colour, even or odd, run in
  // parallel).
  kernels::particles::SlabSchedule<Mem> schedule_;
  bool schedule_current_ = false;  // schedule_ is that of the last rebuild's positions
  // Kept across rebuilds so that a rebuild allocates only what the Verlet list needs.
  kernels::particles::Bins<Mem> bins_;
  Kokkos::View<unsigned char*, Mem> permute_scratch_;
  Kokkos::View<int*, Mem> destination_;  // a migration's destination ranks (-1: removed)
  mesh::particles::MigrationBuffers<Mem> migration_buffers_;

  mesh::particles::ParticleHalo<ExecSpace> halo_;  // the ghosts' plan, refreshed each step

  double time_ = 0;
  long long steps_ = 0;
  bool need_rebuild_ = true;
  bool forces_valid_ = false;
  mutable bool pending_kick_ = false;
  bool profiling_ = false;
  DemTimers timers_;
};

}  // namespace amphora::physics::dem
