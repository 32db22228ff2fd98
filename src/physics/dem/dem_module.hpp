#pragma once
// The DEM physics module for scenes: a box (settling bed) or a rotating drum, particles of one
// or two materials with polydisperse radii, lattice or random insertion over time, and the
// diagnostics (energies, contacts, overlap; the drum's regime) the run driver writes.
#include <memory>

#include "physics/dem/dem_system.hpp"
#include "physics/dem/drum_regime.hpp"
#include "physics/dem/insertion.hpp"
#include "physics/module.hpp"
#include "base/parameters.hpp"

namespace amphora::physics::dem {

/// The scene table `[dem]`.
ParamTable parameter_table();

/// How a coupling wants the particles split over the ranks (DemConfig::layout and
/// min_halo_width); the default is the DEM's own.
struct DemSplit {
  mesh::particles::DecompositionLayout layout;
  double min_halo_width = 0;
};

class DemModule final : public Module {
 public:
  using System = DemSystem<kernels::DefaultExecSpace>;
  DemModule(const Parameters& p, const Communicator& comm, const DemSplit& split = {});

  std::string name() const override { return "dem"; }
  double stable_dt() const override { return dt_limit_; }
  void set_time_step(double dt) override;
  void advance(double t, double dt) override;
  long long work_per_step() const override;
  std::string work_unit() const override { return "particle-steps"; }
  std::vector<OutputBlock> output(double t) const override;
  Diagnostics diagnostics(double t) const override;
  std::string error_diagnostic() const override { return "max_overlap"; }
  std::optional<NonFiniteReport> find_nonfinite() const override;
  std::vector<StateBlock> state() const override;
  void restore(const std::vector<StateBlock>& blocks) override;
  std::vector<std::string> owned_blocks() const override;

  const System& system() const { return *system_; }
  /// The system itself, for a coupling that steps it (CFD-DEM).
  System& system() { return *system_; }
  /// The drum's regime now (drum geometry only). Collective.
  DrumClassification drum_regime() const;

 private:
  void insert_due(double t);
  void update_drum(double t);
  /// All ranks' particles on rank 0, sorted by gid (empty elsewhere).
  System::HostState gather() const;

  Communicator comm_;
  bool drum_ = false;
  double gravity_ = 9.81;
  double box_[3] = {0, 0, 0};
  double floor_ = 0.0;  ///< the box's floor (z)
  double drum_radius_ = 0, drum_length_ = 0, drum_omega_ = 0, settle_time_ = 0;
  bool drum_turning_ = false;
  RadiusDistribution radii_;
  std::vector<double> material_fractions_;
  std::string insertion_;
  long long particle_count_ = 0;
  double insertion_rate_ = 0, insertion_velocity_ = 0, insertion_interval_ = 0.005;
  int insertion_attempts_ = 100;
  std::uint64_t seed_ = 1;
  long long inserted_ = 0, next_event_ = 0;
  double dt_limit_ = 0, rayleigh_ = 0, hertz_ = 0, impact_speed_ = 0;
  bool allow_large_dt_ = false;
  // Time averages of the drum's regime metrics once it has turned a quarter revolution:
  // samples, upper fraction, airborne fraction, surface angle, surface deviation.
  mutable double regime_sums_[5] = {0, 0, 0, 0, 0};
  std::unique_ptr<System> system_;
};

}  // namespace amphora::physics::dem
