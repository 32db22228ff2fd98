#include "physics/poisson_fem/poisson_fem.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kernels/blas1.hpp"
#include "kernels/reductions.hpp"
#include "mesh/box_decomposition.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "kernels/host_vector.hpp"
#include "physics/poisson_fem/sine_error_norms.hpp"
#include "physics/poisson_fem/sine_solution.hpp"
#include "solvers/matrix_free/error_norms.hpp"
#include "solvers/matrix_free/load_vector.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"
#include "solvers/matrix_free/multigrid.hpp"

namespace amphora::physics::poisson_fem {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace poisson_fem_kernels {

template <int dim>
class PoissonFem final : public Module {
 public:
  using Exec = kernels::DefaultExecSpace;
  using Space = mesh::hex::DistributedQkSpace<dim, Exec>;
  using Operator = solvers::matrix_free::DistributedOperator<dim, Exec>;
  using Vector = typename Operator::Vector;

  PoissonFem(const Parameters& p, const Communicator& comm) : comm_(comm) {
    auto m = mesh::hex::unit_cube<dim>(static_cast<int>(p.integer("cells")));
    const double amplitude = p.real("deformation");
    if (amplitude > 0.0) m.deformation = mesh::hex::sinusoidal_deformation(dim, amplitude);
    const std::string geometry = p.string("geometry");
    if (geometry == "cartesian" && amplitude > 0.0)
      throw std::invalid_argument(
          "poisson_fem.geometry = \"cartesian\" needs deformation = 0 (allowed for curved "
          "cells: stored, on_the_fly)");
    const int cells = static_cast<int>(p.integer("cells"));
    if (cells < comm.size())
      throw mesh::DecompositionError("more ranks (" + std::to_string(comm.size()) +
                                     ") than cells (" + std::to_string(cells) +
                                     ") along the last direction: each rank "
                                     "needs a slab of at least one cell");
    space_ = std::make_unique<Space>(m, static_cast<int>(p.integer("degree")), comm);
    n_global_ = space_->n_global();
    typename Operator::Local::Options o;
    o.kind = solvers::matrix_free::OperatorKind::laplace;
    o.geometry = geometry == "cartesian"    ? solvers::matrix_free::GeometryMode::cartesian
                 : geometry == "on_the_fly" ? solvers::matrix_free::GeometryMode::on_the_fly
                                            : solvers::matrix_free::GeometryMode::stored;
    A_ = std::make_unique<Operator>(*space_, o);
    multigrid_ = p.string("solver") == "multigrid";
    control_.relative_tolerance = p.real("tolerance");
    control_.max_iterations = static_cast<int>(p.integer("max_iterations"));
    u_ = Vector("amphora::PoissonFem::u", space_->n_local());
  }

  std::string name() const override { return "poisson_fem"; }
  double stable_dt() const override { return 1.0; }  // steady: one step solves
  void advance(double, double) override {
    if (solved_) return;
    const Exec exec;
    const long n = space_->n_local();
    const auto& local = space_->local();
    const SineSolution<dim> exact;
    const Vector f = kernels::to_view<typename Exec::memory_space>(
        local.interpolate([&](const mesh::hex::Point3& x, int) { return exact.source(x); }));
    const Vector b = solvers::matrix_free::load_vector(
        exec, local, f, A_->local().options().geometry, local.degree() + 2);
    space_->compress_add(exec, b);
    kernels::blas1::fill(exec, u_, 0.0);
    const auto dot = space_->inner_product();
    if (multigrid_) {
      const solvers::matrix_free::MatrixFreeMultigrid<dim, Exec> mg(exec, *A_);
      result_ = solvers::conjugate_gradient(exec, *A_, b, u_, control_, mg, dot);
    } else {
      Vector d("d", n);
      A_->compute_diagonal(exec, d);
      kernels::blas1::reciprocal(exec, d);
      result_ = solvers::conjugate_gradient(exec, *A_, b, u_, control_,
                                            solvers::JacobiPreconditioner<Vector>{d}, dot);
    }
    if (!result_.converged)
      throw std::runtime_error("poisson_fem: CG did not reach the tolerance " +
                               std::to_string(control_.relative_tolerance) + " in " +
                               std::to_string(result_.iterations) + " iterations (residual " +
                               std::to_string(result_.final_residual / result_.rhs_norm) + ")");
    space_->update_ghosts(exec, u_);
    // Each rank integrates over its own cells.
    const solvers::matrix_free::ErrorNorms e =
        solvers::matrix_free::error_norms(exec, local, u_, SineSolution<dim>{});
    errors_ = {std::sqrt(comm_.sum(e.l2 * e.l2)), std::sqrt(comm_.sum(e.h1semi * e.h1semi))};
    solved_ = true;
  }
  long long work_per_step() const override { return n_global_; }
  std::string work_unit() const override { return "DoF-solves"; }

  std::vector<OutputBlock> output(double) const override {
    // One block per rank: its slab's nodes, the shared layer included so the pieces join.
    const auto& lat = space_->local().lattice();
    const long n_nodes = lat.n_nodes();
    auto xh =
        Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), space_->local().coordinates());
    auto uh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), u_);
    OutputBlock b;
    b.name = comm_.size() > 1 ? "solution_" + std::to_string(comm_.rank()) : "solution";
    b.curvilinear = true;
    for (int d = 0; d < dim; ++d) b.nodes[d] = lat.nodes[d];
    b.x.resize(n_nodes);
    b.y.resize(n_nodes);
    b.z.assign(n_nodes, 0.0);
    std::vector<double> u(n_nodes), exact(n_nodes), err(n_nodes);
    const SineSolution<dim> s;
    for (long node = 0; node < n_nodes; ++node) {
      int ijk[3] = {0, 0, 0};
      long rest = node;
      for (int d = 0; d < dim; ++d)
        ijk[d] = static_cast<int>(rest % lat.nodes[d]), rest /= lat.nodes[d];
      double x[3] = {0.0, 0.0, 0.0};
      for (int d = 0; d < dim; ++d) x[d] = xh(d * n_nodes + node);
      b.x[node] = x[0];
      b.y[node] = x[1];
      b.z[node] = x[2];
      u[node] = uh(lat.dof_index(ijk));
      exact[node] = s.value(x);
      err[node] = u[node] - exact[node];
    }
    b.fields = {{"u", u}, {"u_exact", exact}, {"error", err}};
    return {b};
  }

  Diagnostics diagnostics(double) const override {
    return {{"dofs", static_cast<double>(n_global_)},
            {"iterations", static_cast<double>(result_.iterations)},
            {"relative_residual",
             result_.rhs_norm > 0 ? result_.final_residual / result_.rhs_norm : 0.0},
            {"l2_error", errors_.l2},
            {"h1_error", errors_.h1semi}};
  }
  std::string error_diagnostic() const override { return "l2_error"; }
  std::optional<NonFiniteReport> find_nonfinite() const override {
    const long i = kernels::reduce::first_nonfinite(Exec(), u_);
    if (i < 0) return std::nullopt;
    return NonFiniteReport{"u", "solution", i, 0.0, {}, {}};
  }
  // The checkpoint holds the whole solution in global DoF order (the owned parts in rank
  // order are exactly that), written by rank 0: it restarts on any rank count.
  std::vector<StateBlock> state() const override {
    auto uh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), u_);
    const std::vector<double> u =
        comm_.gatherv(std::vector<double>(uh.data(), uh.data() + space_->n_owned()));
    if (!comm_.is_root()) return {};
    return {{"solution",
             {{"u", u},
              {"solved", {solved_ ? 1.0 : 0.0}},
              {"errors",
               {errors_.l2, errors_.h1semi, double(result_.iterations), result_.final_residual,
                result_.rhs_norm}}}}};
  }
  void restore(const std::vector<StateBlock>& blocks) override {
    for (const auto& b : blocks) {
      if (b.name != "solution") continue;
      for (const auto& [key, v] : b.arrays) {
        if (key == "u") {
          if (static_cast<long>(v.size()) != n_global_)
            throw std::runtime_error("poisson_fem: checkpoint holds " + std::to_string(v.size()) +
                                     " DoFs, the scene has " + std::to_string(n_global_));
          auto uh = Kokkos::create_mirror_view(u_);
          for (long i = 0; i < space_->n_local(); ++i) uh(i) = v[space_->global_index(i)];
          Kokkos::deep_copy(u_, uh);
        } else if (key == "solved") {
          solved_ = v.at(0) != 0.0;
        } else if (key == "errors") {
          errors_ = {v.at(0), v.at(1)};
          result_.iterations = static_cast<int>(v.at(2));
          result_.final_residual = v.at(3);
          result_.rhs_norm = v.at(4);
        }
      }
    }
  }
  std::vector<std::string> owned_blocks() const override { return {"solution"}; }

 private:
  Communicator comm_;
  std::unique_ptr<Space> space_;
  std::unique_ptr<Operator> A_;
  long n_global_ = 0;
  bool multigrid_ = true;
  solvers::SolverControl control_;
  solvers::SolverResult result_;
  solvers::matrix_free::ErrorNorms errors_;
  Vector u_;
  bool solved_ = false;
};

}  // namespace poisson_fem_kernels
using namespace poisson_fem_kernels;

ParamTable parameter_table() {
  return {"poisson_fem",
          "-lap u = f on curved Q_k hexahedra of the unit square/cube, manufactured sine solution",
          {
              int_param("dim", 3, at_least(2) & at_most(3), "space dimension"),
              int_param("degree", 4, at_least(1) & at_most(mesh::hex::max_qk_degree),
                        "polynomial degree k of Q_k"),
              int_param("cells", 8, at_least(1) & at_most(1024), "cells per direction"),
              real_param("deformation", 0.05, "1", at_least(0.0) & at_most(0.1),
                         "amplitude of the sinusoidal deformation (0: Cartesian)"),
              string_param("geometry", std::string("stored"),
                           "how geometry reaches the quadrature points",
                           {"cartesian", "stored", "on_the_fly"}),
              string_param("solver", std::string("multigrid"), "preconditioner of CG",
                           {"multigrid", "jacobi"}),
              real_param("tolerance", 1e-10, "1", above(0.0) & below(1.0),
                         "relative residual of the CG solve"),
              int_param("max_iterations", 2000, at_least(1), "CG iteration limit"),
          }};
}

std::unique_ptr<Module> create(const Parameters& p, const Communicator& comm) {
  if (p.integer("dim") == 2) return std::make_unique<PoissonFem<2>>(p, comm);
  return std::make_unique<PoissonFem<3>>(p, comm);
}

}  // namespace amphora::physics::poisson_fem
