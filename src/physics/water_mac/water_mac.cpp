#include "physics/water_mac/water_mac.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/blas1.hpp"
#include "kernels/host_vector.hpp"
#include "kernels/mac/level_set.hpp"
#include "kernels/mac/projection.hpp"
#include "kernels/mac/tall_cell_advection.hpp"
#include "kernels/mac/tall_cell_transfer.hpp"
#include "kernels/reductions.hpp"
#include "mesh/box_decomposition.hpp"
#include "mesh/mac/lattice_halo.hpp"
#include "mesh/mac/tall_cell_grid.hpp"
#include "physics/phase_times.hpp"
#include "physics/water_mac/stoker_dam_break.hpp"
#include "physics/water_mac/water_diagnostics.hpp"
#include "physics/water_mac/water_scenes.hpp"
#include "solvers/mac/lattice_pressure.hpp"
#include "solvers/mac/mac_multigrid.hpp"

namespace amphora::physics::water_mac {

// The module lives in a named namespace: CUDA takes no extended lambda in an anonymous one.
using Exec = kernels::DefaultExecSpace;
using Mem = Exec::memory_space;
using Vector = Kokkos::View<double*, Mem>;
using Types = Kokkos::View<kernels::mac::MacCellType*, Mem>;
using Stencil = kernels::mac::PoissonStencil<Mem>;
using kernels::mac::Staggering;

class WaterMac final : public Module {
 public:
  WaterMac(const Parameters& p, const Communicator& comm) : comm_(comm) {
    scene_ = p.string("scene");
    const int nx = static_cast<int>(p.integer("cells_x")),
              ny = static_cast<int>(p.integer("cells_y")),
              nz = static_cast<int>(p.integer("cells_z"));
    global_ = kernels::mac::MacGrid{nx, ny, nz, p.real("length_x") / nx, {0.0, 0.0, 0.0}};
    cfl_ = p.real("cfl");
    // Blocks split horizontally (columns whole), each at least as wide as a trace reaches into
    // its neighbours: sqrt(3) cfl cells (the speed against its largest component) plus the
    // interpolation's cell and one to spare.
    trace_reach_ = static_cast<int>(std::ceil(std::sqrt(3.0) * cfl_)) + 2;
    decomposition_ = std::make_unique<mesh::BoxDecomposition>(
        mesh::Index3{nx, ny, nz}, std::array<bool, 3>{false, false, false}, comm.size(),
        comm.size() > 1 ? trace_reach_ : 1, std::array<bool, 3>{true, false, true});
    block_ = mesh::mac::MacBlock::of(*decomposition_, comm.get(), comm.rank());
    const mesh::Box box = decomposition_->box(comm.rank());
    const double h = global_.h;
    grid_ = kernels::mac::MacGrid{
        box.extent(0), ny, box.extent(2), h, {box.lo[0] * h, 0.0, box.lo[2] * h}};
    halo_ = mesh::mac::LatticeGhostExchange(block_);
    edges_ = block_.edges();
    gravity_ = p.real("gravity");
    rho_ = p.real("density");
    backend_ = solvers::mac::parse_pressure_backend(p.string("solver"));
    control_.relative_tolerance = p.real("tolerance");
    control_.max_iterations = static_cast<int>(p.integer("max_iterations"));
    reinit_ = static_cast<int>(p.integer("reinitialise_iterations"));
    optical_depth_ = static_cast<int>(p.integer("optical_depth"));
    column_width_ = p.real("column_width");
    if (scene_ == "wet_dam_break") {
      reservoir_depth_ = p.real("reservoir_depth");
      tailwater_depth_ = p.real("tailwater_depth");
      if (tailwater_depth_ >= reservoir_depth_)
        throw std::invalid_argument(
            "water_mac.tailwater_depth = " + std::to_string(tailwater_depth_) +
            " m must be below water_mac.reservoir_depth = " + std::to_string(reservoir_depth_) +
            " m (the water behind the dam)");
      stoker_ = stoker_dam_break(gravity_, reservoir_depth_, tailwater_depth_);
    }
    // the band of uniform cells must hold a whole semi-Lagrangian trace and the extrapolation
    const int band = static_cast<int>(std::ceil(cfl_)) + 2;
    if (optical_depth_ > 0 && optical_depth_ < band) {
      std::ostringstream m;
      m << "water_mac.optical_depth = " << optical_depth_
        << " is below the band the advection needs: with cfl = " << cfl_
        << " a sub-step traces up to " << std::ceil(cfl_)
        << " cells and the velocity is extrapolated 2 more, so "
        << "optical_depth must be at least " << band << " (or 0 for no tall cells)";
      throw std::invalid_argument(m.str());
    }
    if (backend_ == solvers::mac::PressureBackend::multigrid) {
      const std::string e = solvers::mac::multigrid_size_error(
          global_, solvers::mac::MacMultigridOptions{}.max_coarse_cells);
      if (!e.empty()) throw std::invalid_argument("water_mac (solver = \"multigrid\"): " + e);
    }
    if (block_.split() && backend_ == solvers::mac::PressureBackend::mic0)
      throw std::invalid_argument("water_mac.solver = \"mic0\" runs on one rank (on " +
                                  std::to_string(comm.size()) +
                                  " ranks use \"multigrid\" or \"hypre\")");
    extrapolation_layers_ = band;
    allocate();
    initialise(p);
  }

  std::string name() const override { return "water_mac"; }

  double stable_dt() const override {
    // the CFL step of the fastest of: the flow now, and free fall / gravity waves over the box
    const double speed = std::max(max_speed(), std::sqrt(gravity_ * grid_.h * grid_.ny));
    return grid_.h / std::max(speed, 1e-12);
  }

  void advance(double, double dt) override {
    phases_.start();
    double done = 0.0;
    while (done < dt * (1.0 - 1e-12)) {
      const double now = max_speed();
      const double speed = now + gravity_ * std::min(dt - done, grid_.h / std::max(now, 1e-3));
      double sub = std::min(dt - done, cfl_ * grid_.h / std::max(speed, 1e-12));
      if (optical_depth_ > 0) {
        // the explicit upwind step in the tall cells needs a Courant sum below one there
        const double tall =
            comm_.max(kernels::mac::tall_cell_speed(Exec(), tall_, u_, v_, w_)) + gravity_ * sub;
        sub = std::min(sub, grid_.h / std::max(tall, 1e-12));
      }
      if (dt - done - sub < 1e-3 * sub) sub = dt - done;
      phases_.lap(step_control);
      substep(sub);
      done += sub;
    }
  }

  long long work_per_step() const override { return global_.cells(); }
  std::string work_unit() const override { return "cell-steps"; }

  std::vector<OutputBlock> output(double) const override {
    const kernels::mac::MacGrid& g = grid_;
    OutputBlock b;
    b.name = comm_.size() > 1 ? "water_" + std::to_string(comm_.rank())
                              : "water";  // one piece per block
    for (int i = 0; i < g.nx; ++i) b.x.push_back(g.origin[0] + (i + 0.5) * g.h);
    for (int j = 0; j < g.ny; ++j) b.y.push_back(g.origin[1] + (j + 0.5) * g.h);
    for (int k = 0; k < g.nz; ++k) b.z.push_back(g.origin[2] + (k + 0.5) * g.h);
    const auto phi = kernels::to_std_vector(phi_), p = kernels::to_std_vector(p_);
    const auto u = kernels::to_std_vector(u_), v = kernels::to_std_vector(v_),
               w = kernels::to_std_vector(w_);
    std::vector<double> fphi, fp, fu, fv, fw, fspeed;
    for (int k = 0; k < g.nz; ++k)
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
          const int c = g.index(i, j, k);
          fphi.push_back(phi[c]);
          fp.push_back(p[c]);
          const double uc = 0.5 * (u[c] + u[c + 1]), vc = 0.5 * (v[c] + v[c + g.stride_y()]),
                       wc = 0.5 * (w[c] + w[c + g.stride_z()]);
          fu.push_back(uc);
          fv.push_back(vc);
          fw.push_back(wc);
          fspeed.push_back(std::sqrt(uc * uc + vc * vc + wc * wc));
        }
    b.fields = {{"phi", fphi}, {"pressure", fp}, {"u", fu},
                {"v", fv},     {"w", fw},        {"speed", fspeed}};
    return {b};
  }

  Diagnostics diagnostics(double t) const override {
    Diagnostics d;
    d.emplace_back("volume", volume());
    d.emplace_back("max_speed", max_speed());
    d.emplace_back("pressure_iterations", last_iterations_);
    // uniform cells: the fluid cells of the last projection (the types have not changed since),
    // counted here rather than every sub-step
    const long unknowns = optical_depth_ > 0 ? last_unknowns_ : substeps_ > 0 ? count_fluid() : 0;
    d.emplace_back("pressure_unknowns", double(unknowns));
    d.emplace_back("substeps", double(substeps_));
    if (scene_ == "dam_break") {
      const double a = column_width_, Z = front() / a, T = t * std::sqrt(2.0 * gravity_ / a);
      d.emplace_back("front_Z", Z);
      d.emplace_back("front_T", T);
      const bool measured = T >= 0.832 && T <= 9.237;
      d.emplace_back("front_error",
                     measured ? (Z - martin_moyce_front(T)) / martin_moyce_front(T) : 0.0);
    } else if (scene_ == "wet_dam_break") {
      // the bore's distance from the dam against Stoker's S t (T = t sqrt(g / h0))
      const double travelled = bore() - column_width_, exact = stoker_.bore_speed * t;
      d.emplace_back("bore_x", travelled);
      d.emplace_back("bore_T", t * std::sqrt(gravity_ / reservoir_depth_));
      d.emplace_back("bore_error", t > 0.0 ? (travelled - exact) / exact : 0.0);
    } else {
      d.emplace_back("surface_height", surface_height());
    }
    return d;
  }
  std::string error_diagnostic() const override {
    return scene_ == "dam_break"       ? "front_error"
           : scene_ == "wet_dam_break" ? "bore_error"
                                       : "max_speed";
  }

  std::optional<NonFiniteReport> find_nonfinite() const override {
    const Exec exec;
    const Vector fields[5] = {phi_, u_, v_, w_, p_};
    const char* names[5] = {"phi", "u", "v", "w", "pressure"};
    // this block's first non-finite entry (field, padded index, x), then the lowest rank's
    double found[3] = {-1.0, 0.0, 0.0};
    for (int f = 0; f < 5 && found[0] < 0; ++f) {
      const int bad = kernels::reduce::first_nonfinite(exec, fields[f]);
      if (bad >= 0 && bad < static_cast<int>(fields[f].extent(0))) {
        int i, j, k;
        grid_.ijk(bad, i, j, k);
        found[0] = f, found[1] = bad, found[2] = grid_.origin[0] + (i + 0.5) * grid_.h;
      }
    }
    const int first =
        static_cast<int>(comm_.min(found[0] >= 0 ? double(comm_.rank()) : double(comm_.size())));
    if (first >= comm_.size()) return std::nullopt;
    MPI_Bcast(found, 3, MPI_DOUBLE, first, comm_.get());
    return NonFiniteReport{names[static_cast<int>(found[0])],
                           comm_.size() > 1 ? "water_" + std::to_string(first) : "water",
                           static_cast<long long>(found[1]),
                           found[2],
                           {},
                           {}};
  }

  // The checkpoint holds the fields on the whole grid's padded lattice (each block's share,
  // the box's ghost layer from the blocks at the box faces), written by rank 0: a run restarts
  // on any number of ranks.
  std::vector<StateBlock> state() const override {
    StateBlock b;
    b.name = "water";
    const std::pair<const char*, Vector> fields[5] = {
        {"phi", phi_}, {"u", u_}, {"v", v_}, {"w", w_}, {"pressure", p_}};
    for (const auto& [name, f] : fields) {
      const std::vector<double> whole = to_global(kernels::to_std_vector(f));
      if (comm_.is_root()) b.arrays.push_back({name, whole});
    }
    if (!comm_.is_root()) return {};
    b.arrays.push_back({"substeps", {double(substeps_)}});
    return {b};
  }
  void restore(const std::vector<StateBlock>& blocks) override {
    speed_ = -1.0;
    phi_buffers_match_below_ = 0;
    stencil_built_from_ = 0;  // the kept stencil's rows are the old state's
    for (const auto& b : blocks)
      for (const auto& [name, a] : b.arrays) {
        if (name == "substeps") substeps_ = static_cast<long>(a.at(0));
        Vector target = name == "phi"        ? phi_
                        : name == "u"        ? u_
                        : name == "v"        ? v_
                        : name == "w"        ? w_
                        : name == "pressure" ? p_
                                             : Vector();
        if (target.extent(0) > 0 && static_cast<long>(a.size()) == global_.padded_size())
          Kokkos::deep_copy(target, kernels::to_view<Mem>(from_global(a)));
      }
    classify();
  }
  std::vector<std::string> owned_blocks() const override { return {"water"}; }
  Diagnostics phase_seconds() const override { return phases_.seconds(); }

 public:  // (CUDA: extended lambdas may not live in private member functions)
  /// The padded-lattice range of the whole grid this rank's block holds in the checkpoint:
  /// its cells, and the ghost layer where it meets the box faces ([lo, hi] inclusive).
  void owned_range(int rank, int lo[3], int hi[3]) const {
    const mesh::Box box = decomposition_->box(rank);
    const int n[3] = {global_.nx, global_.ny, global_.nz};
    for (int d = 0; d < 3; ++d) {
      lo[d] = box.lo[d] == 0 ? -1 : box.lo[d];
      hi[d] = box.lo[d] + box.extent(d) == n[d] ? n[d] : box.lo[d] + box.extent(d) - 1;
    }
  }
  /// This block's padded lattice -> the whole grid's, on rank 0 (empty elsewhere).
  std::vector<double> to_global(const std::vector<double>& local) const {
    if (comm_.size() == 1) return local;
    int lo[3], hi[3];
    owned_range(comm_.rank(), lo, hi);
    const int* o = block_.global_lower.data();
    std::vector<double> mine;
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
          mine.push_back(local[grid_.index(i - o[0], j, k - o[2])]);
    const std::vector<double> all = comm_.gatherv(mine);
    if (!comm_.is_root()) return {};
    std::vector<double> whole(global_.padded_size(), 0.0);
    std::size_t m = 0;
    for (int r = 0; r < comm_.size(); ++r) {
      owned_range(r, lo, hi);
      for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
          for (int i = lo[0]; i <= hi[0]; ++i) whole[global_.index(i, j, k)] = all[m++];
    }
    return whole;
  }
  /// The whole grid's padded lattice -> this block's (its ghost layer included).
  std::vector<double> from_global(const std::vector<double>& whole) const {
    if (comm_.size() == 1) return whole;
    std::vector<double> local(grid_.padded_size(), 0.0);
    const int* o = block_.global_lower.data();
    for (int k = -1; k <= grid_.nz; ++k)
      for (int j = -1; j <= grid_.ny; ++j)
        for (int i = -1; i <= grid_.nx; ++i)
          local[grid_.index(i, j, k)] = whole[global_.index(i + o[0], j, k + o[2])];
    return local;
  }

  void allocate() {
    const long n = grid_.padded_size();
    phi_ = Vector("amphora::water::phi", n);
    phi_tmp_ = Vector("amphora::water::phi_tmp", n);
    phi0_ = Vector("amphora::water::phi0", n);
    u_ = Vector("amphora::water::u", n), v_ = Vector("amphora::water::v", n),
    w_ = Vector("amphora::water::w", n);
    u_tmp_ = Vector("amphora::water::u_tmp", n), v_tmp_ = Vector("amphora::water::v_tmp", n);
    w_tmp_ = Vector("amphora::water::w_tmp", n);
    p_ = Vector("amphora::water::p", n);
    b_ = Vector("amphora::water::b", n);
    stencil_ = Stencil(grid_);
    stencil_built_from_ = 0;
    type_ = Types("amphora::water::type", n);
    tall_ = kernels::mac::TallCellColumns<Mem>(grid_, block_.edges());
    fitted_tall_ = kernels::mac::TallCellColumns<Mem>(grid_, block_.edges());
    solid_ = Kokkos::View<std::uint8_t*, Mem>("amphora::water::solid", n);
    valid_ = Kokkos::View<std::uint8_t*, Mem>("amphora::water::valid", n);
    if (block_.split()) {
      // the advection's copies of the fields on the block widened into its neighbours, and the
      // tall cells there (from the widened cell types)
      wide_ = halo_.widened(grid_, trace_reach_);
      const long nw = wide_.grid.padded_size();
      for (Vector* f : {&wide_phi_, &wide_u_, &wide_v_, &wide_w_})
        *f = Vector("amphora::water::wide", nw);
      wide_tall_ = kernels::mac::TallCellColumns<Mem>(wide_.grid);
      if (optical_depth_ > 0) wide_type_ = Types("amphora::water::wide_type", nw);
    }
  }

  /// The initial water and the solid floor (water_scenes.cpp), then the cell types, the
  /// solid faces and the velocity's first extrapolation.
  void initialise(const Parameters& p) {
    const WaterScene scene{scene_, column_width_, reservoir_depth_, tailwater_depth_};
    const InitialWater init = initial_water(p, scene, grid_, global_, comm_);
    Kokkos::deep_copy(phi_, kernels::to_view<Mem>(init.phi));
    Kokkos::deep_copy(v_, kernels::to_view<Mem>(init.v));
    Kokkos::deep_copy(solid_, kernels::to_view<Mem>(init.solid));
    halo_.exchange(Exec(), grid_, solid_);
    classify();
    // the solids do not move: their faces are listed once (classify() gave the ghost cells' types)
    for (int d = 0; d < 3; ++d)
      solid_faces_[d] = kernels::mac::solid_faces(Exec(), grid_, d, type_, edges_);
    fit_velocity_in_tall_cells();
    extrapolate_velocity();
  }

  /// The velocity in the tall cells linear in height, keeping each column's momentum (after the
  /// grid follows the surface; the tall-cell advection relies on it).
  void fit_velocity_in_tall_cells() {
    if (optical_depth_ == 0) return;
    kernels::mac::fit_linear_in_tall_cells(Exec(), tall_, 0, u_, fitted_tall_);
    kernels::mac::fit_linear_in_tall_cells(Exec(), tall_, 1, v_, fitted_tall_);
    kernels::mac::fit_linear_in_tall_cells(Exec(), tall_, 2, w_, fitted_tall_);
  }

  /// Cell types from the level set (the level set's and the types' ghost cells from the
  /// neighbouring blocks), and the tall-cell columns that follow them.
  void classify() {
    kernels::mac::classify_cells(Exec(), grid_, solid_, phi_, type_);
    halo_.exchange(Exec(), grid_, phi_);
    halo_.exchange(Exec(), grid_, type_);
    // without tall cells the columns stay as allocated: terrain = band = 0, no tall rows
    if (optical_depth_ > 0) {
      // the columns the velocity is linear on so far (nothing before the first fit)
      Kokkos::deep_copy(fitted_tall_.terrain, tall_.terrain);
      Kokkos::deep_copy(fitted_tall_.band, tall_.band);
      kernels::mac::find_tall_cell_columns(Exec(), type_, optical_depth_, tall_);
      lowest_band_ = kernels::mac::lowest_band(Exec(), tall_, type_);
      if (block_.split()) {
        halo_.fill_widened(Exec(), grid_, type_, wide_, wide_type_);
        kernels::mac::find_tall_cell_columns(Exec(), wide_type_, optical_depth_, wide_tall_);
      }
    }
  }

  void substep(double dt) {
    const Exec exec;
    const kernels::mac::MacGrid& g = grid_;
    speed_ = -1.0;  // the velocity changes from here on
    // 1. advection of the level set and the velocity (all from the old velocity; on the
    //    tall-cell grid of the last sub-step, uniform everywhere without tall cells)
    //    velocity only where the water can be after the step: the surface moves at most
    //    sqrt(3) cfl cells (a trace), plus one for the interpolation, with margin
    const double reach = (2 * std::ceil(cfl_) + 3) * g.h;
    // on a block the traces read the fields widened into the neighbouring blocks; on one
    // block the fields themselves (offset zero)
    const bool split = block_.split();
    if (split) {
      halo_.fill_widened(exec, g, phi_, wide_, wide_phi_);
      halo_.fill_widened(exec, g, u_, wide_, wide_u_);
      halo_.fill_widened(exec, g, v_, wide_, wide_v_);
      halo_.fill_widened(exec, g, w_, wide_, wide_w_);
    }
    const auto& T = split ? wide_tall_ : tall_;
    const Vector P = split ? wide_phi_ : phi_, U = split ? wide_u_ : u_, V = split ? wide_v_ : v_,
                 W = split ? wide_w_ : w_;
    const int* o = wide_.offset;
    // the level set below the lowest band lies in tall cells (kept) or under the terrain: its
    // kernels start there, phi_ and phi_tmp_ holding the same rows below (deep splash 3.6 m,
    // D = 20: rows 210.. of 256)
    const int first_row = lowest_band_;
    match_phi_buffers_below(first_row);
    kernels::mac::advect(exec, T, Staggering::centre, P, phi_tmp_, U, V, W, dt, P, reach, g, o,
                         first_row);
    kernels::mac::advect(exec, T, Staggering::x, U, u_tmp_, U, V, W, dt, P, reach, g, o);
    kernels::mac::advect(exec, T, Staggering::y, V, v_tmp_, U, V, W, dt, P, reach, g, o);
    kernels::mac::advect(exec, T, Staggering::z, W, w_tmp_, U, V, W, dt, P, reach, g, o);
    std::swap(phi_, phi_tmp_);
    std::swap(u_, u_tmp_), std::swap(v_, v_tmp_), std::swap(w_, w_tmp_);
    phases_.lap(advection);
    // 2. reinitialisation towards a signed distance
    if (reinit_ > 0) {
      for (int it = 0; it < reinit_; ++it) {
        halo_.exchange(exec, g, phi_);
        // phi0 with its ghost layer: the subcell fix reads it across block faces
        if (it == 0) Kokkos::deep_copy(exec, phi0_, phi_);
        kernels::mac::reinitialise_step(exec, tall_, phi0_, phi_, phi_tmp_, edges_, first_row);
        std::swap(phi_, phi_tmp_);
      }
    }
    phases_.lap(reinitialisation);
    classify();
    // the grid rebuilt to follow the surface: the velocity in its tall cells becomes linear in
    // height, keeping each column's momentum
    fit_velocity_in_tall_cells();
    // 3. gravity, on the y faces inside the box
    const double dv = gravity_ * dt;
    const auto v = v_;
    const kernels::mac::MacGrid gg = g;
    Kokkos::parallel_for(
        "amphora::water::gravity",
        Kokkos::MDRangePolicy<Exec, Kokkos::Rank<3>>(exec, {0, 1, 0}, {g.nz, g.ny, g.nx}),
        KOKKOS_LAMBDA(int k, int j, int i) { v(gg.index(i, j, k)) -= dv; });
    phases_.lap(cell_types);
    // 4. projection
    project(dt);
    extrapolate_velocity();
    phases_.lap(extrapolation);
    ++substeps_;
  }

  void project(double dt) {
    const Exec exec;
    const kernels::mac::MacGrid& g = grid_;
    kernels::mac::MacBoxBoundaries box;
    box.fill(kernels::mac::MacBoundary::wall);
    box[3] = kernels::mac::MacBoundary::open;
    // The stencil is kept between sub-steps and rebuilt from the row under the lowest band up
    // (from the lowest of this sub-step's and the last one's): below it every cell is fluid or
    // solid now and was at the last build, so its rows are what a build gives (tall cells; all
    // rows without them). Deep splash, 7.6 m pool: a fifth of the rows. On a split grid the
    // lowest band of all blocks: the cells beside a block face read the neighbour's.
    const int from = optical_depth_ > 0 ? row_under_on_every_block(lowest_band_) : 0;
    const int rebuilt_from = std::min(from, stencil_built_from_);
    kernels::mac::build_poisson_stencil(exec, g, type_, phi_, block_.faces(box), stencil_,
                                        rebuilt_from);
    stencil_built_from_ = from;
    coarse_stencils_.unchanged_below = rebuilt_from;  // the multigrid's coarse levels likewise
    const Stencil& A = stencil_;
    halo_.exchange(exec, g, A.cx);  // the ghost cells' + faces: this block's - faces
    halo_.exchange(exec, g, A.cz);
    kernels::mac::enforce_solid_faces(exec, solid_faces_[0], u_);
    kernels::mac::enforce_solid_faces(exec, solid_faces_[1], v_);
    kernels::mac::enforce_solid_faces(exec, solid_faces_[2], w_);
    kernels::mac::pressure_rhs(exec, g, type_, u_, v_, w_, rho_, dt, b_);
    solvers::mac::LatticePressure<Exec> pressure(exec, backend_, optical_depth_, A, block_, b_, p_,
                                                 &coarse_stencils_);
    phases_.lap(pressure_setup);
    const solvers::SolverResult r = pressure.solve(exec, control_);
    phases_.lap(pressure_solve);
    if (optical_depth_ > 0) last_unknowns_ = pressure.global_unknowns();  // the last solve's
    last_iterations_ = r.iterations;
    if (!r.converged)
      throw std::runtime_error(
          "water_mac: the pressure solve did not reach the relative residual " +
          std::to_string(control_.relative_tolerance) + " in " + std::to_string(r.iterations) +
          " iterations (reached " +
          std::to_string(r.final_residual / std::max(r.rhs_norm, 1e-300)) + ") at sub-step " +
          std::to_string(substeps_));
    halo_.exchange(exec, g, p_);
    kernels::mac::subtract_pressure_gradient(exec, g, 0, type_, phi_, p_, rho_, dt, u_, edges_);
    kernels::mac::subtract_pressure_gradient(exec, g, 1, type_, phi_, p_, rho_, dt, v_, edges_);
    kernels::mac::subtract_pressure_gradient(exec, g, 2, type_, phi_, p_, rho_, dt, w_, edges_);
    phases_.lap(projection);
  }

  void extrapolate_velocity() {
    const Exec exec;
    const kernels::mac::MacGrid& g = grid_;
    const Vector faces[3] = {u_, v_, w_};
    const int first_row = kernels::mac::lowest_air_row(exec, g, type_);
    // The layers read the marks from one row below the lowest air row of any block on (across a
    // block face, the neighbour's too). Below that row a face lies between fluid cells (known) or
    // touches a solid or the box (zero already), so the marks there are never needed and nothing
    // is cleared: under deep water most rows are skipped.
    const int marked_from = row_under_on_every_block(first_row);
    for (int d = 0; d < 3; ++d) {
      // faces next to fluid keep their values; solid and box faces are zero (the projection
      // set them), the rest are filled layer by layer from known neighbours
      kernels::mac::mark_fluid_faces(exec, g, d, type_, valid_, edges_, marked_from);
      const auto f = faces[d];
      const auto valid = valid_;
      const int ex = g.nx + (d == 0), ey = g.ny + (d == 1), ez = g.nz + (d == 2);
      Kokkos::parallel_for(
          "amphora::water::clear_unknown_faces",
          Kokkos::MDRangePolicy<Exec, Kokkos::Rank<3>>(exec, {0, std::min(marked_from, ey), 0},
                                                       {ez, ey, ex}),
          KOKKOS_LAMBDA(int k, int j, int i) {
            const int c = g.index(i, j, k);
            if (!valid(c)) f(c) = 0.0;
          });
      // each layer reads the last across the blocks' faces
      halo_.exchange(exec, g, faces[d]);
      halo_.exchange(exec, g, valid_);
      for (int layer = 2; layer < 2 + extrapolation_layers_; ++layer) {
        kernels::mac::extrapolate_layer(exec, g, d, type_, faces[d], valid_, layer, edges_,
                                        first_row);
        halo_.exchange(exec, g, faces[d]);
        halo_.exchange(exec, g, valid_);
      }
    }
  }

  /// The row under the lowest of every block's `row` (0 at the bottom): kernels starting there
  /// see, across a block face, the neighbour's rows that may differ too.
  int row_under_on_every_block(int row) const {
    return std::max(static_cast<int>(comm_.min(double(row))) - 1, 0);
  }

  /// Makes phi_tmp_ equal phi_ in the rows below first_row (copying the rows that differ), so a
  /// level-set kernel writing phi_tmp_ from first_row up and the swap after it leave phi_ whole.
  void match_phi_buffers_below(int first_row) {
    const int from = phi_buffers_match_below_;
    phi_buffers_match_below_ = first_row;
    if (first_row <= from) return;
    const kernels::mac::MacGrid g = grid_;
    const auto phi = phi_, tmp = phi_tmp_;
    Kokkos::parallel_for(
        "amphora::water::match_phi_rows",
        Kokkos::MDRangePolicy<Exec, Kokkos::Rank<3>>({0, from, 0}, {g.nz + 2, first_row, g.nx + 2}),
        KOKKOS_LAMBDA(int k, int j, int i) {  // the ghost columns too (i, k = -1 .. n)
          const int c = g.index(i - 1, j, k - 1);
          tmp(c) = phi(c);
        });
  }

  /// Fluid cells (pressure unknowns) over all blocks.
  long count_fluid() const {
    const auto type = type_;
    const kernels::mac::MacGrid g = grid_;
    long n = 0;
    Kokkos::parallel_reduce(
        "amphora::water::count_fluid",
        Kokkos::MDRangePolicy<Exec, Kokkos::Rank<3>>({0, 0, 0}, {g.nz, g.ny, g.nx}),
        KOKKOS_LAMBDA(int k, int j, int i, long& acc) {
          acc += type(g.index(i, j, k)) == kernels::mac::MacCellType::fluid;
        },
        n);
    return static_cast<long>(comm_.sum(static_cast<long long>(n)));
  }

  /// The largest velocity component over every block's faces (not its ghost layer). Measured
  /// once per velocity state: the step control, stable_dt() and the diagnostics all ask for it.
  double max_speed() const {
    if (speed_ < 0.0) speed_ = measured_max_speed();
    return speed_;
  }
  double measured_max_speed() const {
    const auto u = u_, v = v_, w = w_;
    const kernels::mac::MacGrid g = grid_;
    // below the lowest band the faces lie in tall rows, where the velocity is linear in height
    // (only the ends are read), or touch a solid (zero)
    const int below = lowest_band_;
    double m = 0.0;
    if (below > 0)
      for (int d = 0; d < 3; ++d)
        m = std::max(m, kernels::mac::tall_rows_max_abs(Exec(), tall_, d,
                                                        d == 0   ? u
                                                        : d == 1 ? v
                                                                 : w,
                                                        below));
    double above = 0.0;
    Kokkos::parallel_reduce(
        "amphora::water::max_speed",
        Kokkos::MDRangePolicy<Exec, Kokkos::Rank<3>>({0, below, 0}, {g.nz + 1, g.ny + 1, g.nx + 1}),
        KOKKOS_LAMBDA(int k, int j, int i, double& acc) {
          const int c = g.index(i, j, k);
          const bool in_x = i < g.nx, in_y = j < g.ny, in_z = k < g.nz;
          if (in_y && in_z) acc = kernels::math::max(acc, kernels::math::abs(u(c)));
          if (in_x && in_z) acc = kernels::math::max(acc, kernels::math::abs(v(c)));
          if (in_x && in_y) acc = kernels::math::max(acc, kernels::math::abs(w(c)));
        },
        Kokkos::Max<double>(above));
    return comm_.max(std::max(m, above));
  }

  /// Water volume: the cells' water fractions from the level set (smeared over one cell).
  double volume() const {
    const auto phi = phi_;
    const auto solid = solid_;
    const kernels::mac::MacGrid g = grid_;
    double vol = 0.0;
    Kokkos::parallel_reduce(
        "amphora::water::volume",
        Kokkos::MDRangePolicy<Exec, Kokkos::Rank<3>>({0, 0, 0}, {g.nz, g.ny, g.nx}),
        KOKKOS_LAMBDA(int k, int j, int i, double& acc) {
          const int c = g.index(i, j, k);
          if (!solid(c)) acc += kernels::math::clamp(0.5 - phi(c) / g.h, 0.0, 1.0);
        },
        vol);
    return comm_.sum(vol) * g.h * g.h * g.h;
  }

  /// The level set on the host with where this block lies, for the surface diagnostics.
  LevelSetBlock level_set() const {
    return {kernels::to_std_vector(phi_), grid_, global_, block_.global_lower, edges_[1], comm_};
  }
  double front() const { return dam_break_front(level_set()); }
  double bore() const { return bore_position(level_set(), 0.5 * (tailwater_depth_ + stoker_.hm)); }
  double surface_height() const { return mean_surface_height(level_set()); }

 private:
  Communicator comm_;
  std::string scene_;
  kernels::mac::MacGrid global_;  ///< the whole grid
  kernels::mac::MacGrid grid_;    ///< this rank's block of it
  std::unique_ptr<mesh::BoxDecomposition> decomposition_;
  mesh::mac::MacBlock block_;
  mesh::mac::LatticeGhostExchange halo_;
  kernels::mac::MacEdges edges_ = kernels::mac::box_edges();
  int trace_reach_ = 3;
  mesh::mac::WideGrid wide_;
  Vector wide_phi_, wide_u_, wide_v_, wide_w_;
  kernels::mac::TallCellColumns<Mem> wide_tall_;
  Types wide_type_;
  double gravity_ = 9.81, rho_ = 1000.0, cfl_ = 1.0, column_width_ = 0.05;
  double reservoir_depth_ = 0.0, tailwater_depth_ = 0.0;  ///< wet dam break
  StokerDamBreak stoker_;  ///< wet dam break: the shallow-water solution
  solvers::mac::PressureBackend backend_ = solvers::mac::PressureBackend::multigrid;
  solvers::SolverControl control_;
  int reinit_ = 2, optical_depth_ = 0, extrapolation_layers_ = 3;
  mutable double speed_ =
      -1.0;  ///< max_speed() of the current velocity; negative: not measured yet
  Vector phi_, phi_tmp_, phi0_, u_, v_, w_, u_tmp_, v_tmp_, w_tmp_, p_, b_;
  /// phi_ and phi_tmp_ hold the same values in the rows below this one (match_phi_buffers_below)
  int phi_buffers_match_below_ = 0;
  Types type_;
  kernels::mac::TallCellColumns<Mem> tall_;
  /// kernels::mac::lowest_band of tall_ and type_ (0 without tall cells), found with them in
  /// classify()
  int lowest_band_ = 0;
  /// the pressure stencil, kept between sub-steps; its rows from stencil_built_from_ up were
  /// rebuilt last (project())
  Stencil stencil_;
  int stencil_built_from_ = 0;
  /// the tall-cell multigrid's coarse lattice stencils, kept with stencil_ and coarsened again
  /// from the rows it was rebuilt in
  solvers::mac::KeptCoarseStencils<Mem> coarse_stencils_;
  /// tall_ before the last classify(): the velocity's tall cells until it is fitted to tall_
  kernels::mac::TallCellColumns<Mem> fitted_tall_;
  Kokkos::View<std::uint8_t*, Mem> solid_, valid_;
  Kokkos::View<int*, Mem>
      solid_faces_[3];  ///< per component, the faces touching a solid or the box
  long substeps_ = 0;
  int last_iterations_ = 0;
  long last_unknowns_ = 0;
  /// Wall time per phase of a sub-step (the pressure's setup, on tall cells the tall-cell grid,
  /// matrix and multigrid hierarchy; its solve with the prolongation; the gradient in
  /// `projection`).
  enum Phase {
    step_control,
    advection,
    reinitialisation,
    cell_types,
    pressure_setup,
    pressure_solve,
    projection,
    extrapolation
  };
  PhaseTimes phases_{{"step_control", "advection", "reinitialisation", "cell_types",
                      "pressure_setup", "pressure_solve", "projection", "extrapolation"}};
};

std::unique_ptr<Module> create(const Parameters& p, const Communicator& comm) {
  return std::make_unique<WaterMac>(p, comm);
}

}  // namespace amphora::physics::water_mac
