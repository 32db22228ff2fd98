#pragma once
// The flow solver's options, what a step reports and the phases its time is booked to
// (InsSolver, ins_solver.hpp).
#include <string>
#include <vector>

#include "solvers/matrix_free/matrix_free_operator.hpp"
#include "solvers/matrix_free/oseen_multigrid.hpp"

namespace amphora::physics::ins_fem {

enum class InsPreconditioner { multigrid, jacobi };

/// The equations: incompressible Navier-Stokes, or the volume-averaged ones of unresolved
/// CFD-DEM (VANS) with a void fraction, model A or B (kernels::sumfac::VansPoint).
enum class FlowModel { navier_stokes, vans_a, vans_b };

/// VANS: how the continuity's d eps / dt is taken from the void fraction's history. bdf: the
/// velocity's BDF2. filtered: the second-order four-level difference that is blind to a
/// period-two-step alternation, (eps^(n+1) - eps^n / 2 - eps^(n-1) + eps^(n-2) / 2) / dt on
/// uniform steps (BDF2 while the history is short or the step changes): docs/cfd_dem.md.
enum class VoidFractionRate { bdf, filtered };

struct InsOptions {
  FlowModel model = FlowModel::navier_stokes;
  double nu = 0.01;       ///< kinematic viscosity
  double grad_div = 0.0;  ///< grad-div weight gamma
  /// beta of the backflow stabilisation on open (Neumann) faces (backflow_stabilisation.hpp);
  /// 0: none, the plain do-nothing condition.
  double backflow = 0.0;
  /// VANS: the continuity's -d eps / dt; false drops it (Lethe's "void fraction time
  /// derivative"), for beds that barely move: docs/cfd_dem.md.
  bool void_fraction_time_derivative = true;
  VoidFractionRate void_fraction_rate = VoidFractionRate::bdf;
  /// (2 / dt)^2 in the SUPG/PSPG parameter tau. Off by default: with it, tau ~ dt / 2 shrinks
  /// with the step and the pressure stabilisation with it (Bochev, Gunzburger & Shadid 2004,
  /// CMAME 193); the 2D Taylor-Green vortex then lost up to one order of convergence in space
  /// (tests/physics/test_ins_fem.cpp; docs/ins.md).
  bool transient_tau = false;
  double tolerance = 1e-9;  ///< GMRES: relative reduction of each step's residual
  int max_iterations = 5000;
  int restart = 60;
  InsPreconditioner preconditioner = InsPreconditioner::multigrid;
  solvers::matrix_free::OseenMultigridOptions multigrid;
  solvers::matrix_free::GeometryMode geometry = solvers::matrix_free::GeometryMode::stored;
};

/// What one step (or one Picard iteration) of the solver did.
struct InsStepReport {
  int linear_iterations = 0;
  bool converged = false;
  double residual = 0.0;  ///< final linear residual
  /// The multigrid failed to converge within one GMRES cycle and this step (and the run from
  /// here on) fell back to point Jacobi.
  bool fell_back = false;
};

/// The phases a step's time is booked to (PhaseTimes indices).
/// smoother: the V-cycles less their coarse solves (smoothing, residuals, transfers), or the
/// Jacobi preconditioner; coarse: the multigrid's coarsest level.
enum InsPhase { ins_setup = 0, ins_operator = 1, ins_smoother = 2, ins_coarse = 3, ins_other = 4 };
inline std::vector<std::string> ins_phase_names() {
  return {"setup", "operator", "smoother", "coarse solve", "other"};
}

}  // namespace amphora::physics::ins_fem
