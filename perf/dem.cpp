// DEM throughput on a dense bed of monodisperse glass beads (simple-cubic lattice of touching
// 3 mm spheres in a walled box, under gravity): particle-steps per second, and the share of
// time in integration, binning, list build, force and communication. The same system as
// perf/liggghts/dense_bed.in, so the two can be compared on one machine (scripts/bench_dem.sh).
// SettledBed times a poured and settled bed read from a LIGGGHTS data file (the path in
// AMPHORA_SETTLED_BED), the same bed perf/liggghts/settled_bed.in reads
// (scripts/bench_dem_settled.sh). Run at 1 and 2 threads (OMP_NUM_THREADS) and 1 and 2 ranks
// (mpiexec -n 2).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "physics/dem/dem_system.hpp"

namespace {

using amphora::Communicator;
using namespace amphora::physics::dem;
using System = DemSystem<amphora::kernels::DefaultExecSpace>;

constexpr double kD = 0.003;

/// NX x NY x NZ beads, NX = NY = 2.5 NZ / 2 as in the LIGGGHTS input's 50 x 50 x 40.
void bed_shape(long n, int& nx, int& ny, int& nz) {
  nz = static_cast<int>(std::lround(std::cbrt(n * 0.64)));  // 40 for 1e5
  nx = ny = static_cast<int>(std::lround(std::sqrt(double(n) / nz)));
}

/// Glass beads in a box of size L with walls at x, y = 0 and L and at z = 0 (no lid).
DemConfig box_config(const double L[3], double youngs_modulus, double friction, double dt,
                     double radius) {
  Material glass;
  glass.density = 2500;
  glass.youngs_modulus = youngs_modulus;
  glass.poisson_ratio = 0.3;
  glass.restitution = 0.9;
  glass.friction = friction;
  DemConfig c;
  c.materials = {glass};
  c.gravity = {0, 0, -9.81};
  c.dt = dt;
  c.max_radius = radius;
  c.skin = 0.5 * radius;
  c.domain_lo = {0, 0, 0};
  c.domain_hi = {L[0], L[1], L[2]};
  for (int d = 0; d < 3; ++d) {
    Wall lo;
    lo.axis[0] = lo.axis[1] = lo.axis[2] = 0;
    lo.axis[d] = 1;
    c.walls.push_back(lo);
    if (d < 2) {
      Wall hi = lo;
      hi.axis[d] = -1;
      hi.point[d] = L[d];
      c.walls.push_back(hi);
    }
  }
  return c;
}

System make_bed(long n, const Communicator& comm) {
  int nx, ny, nz;
  bed_shape(n, nx, ny, nz);
  const double L[3] = {nx * kD, ny * kD, (nz + 2) * kD};
  System s(box_config(L, 5e6, 0.5, 1e-5, 0.5 * kD), comm);
  std::vector<ParticleSpec> ps;
  ps.reserve(size_t(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        ParticleSpec p;
        p.x[0] = (i + 0.5) * kD;
        p.x[1] = (j + 0.5) * kD;
        p.x[2] = (k + 0.5) * kD;
        p.radius = 0.5 * kD;
        p.gid = static_cast<std::int64_t>(ps.size());
        ps.push_back(p);
      }
  s.add_particles(ps);
  return s;
}

/// The settled bed: 2.5 mm glass (E = 50 MPa, mu = 0.3, dt = 5e-6 s, skin a quarter diameter)
/// at the positions of a LIGGGHTS data file (atom_style granular: id type diameter density x y
/// z), at rest, in the box its header gives.
System read_bed(const std::string& path, const Communicator& comm) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read the settled bed '" + path + "'");
  double L[3] = {0, 0, 0}, lo, hi;
  std::string line, word;
  std::vector<ParticleSpec> ps;
  while (std::getline(in, line)) {
    std::istringstream w(line);
    if (line.find("xlo xhi") != std::string::npos) w >> lo >> hi, L[0] = hi;
    if (line.find("ylo yhi") != std::string::npos) w >> lo >> hi, L[1] = hi;
    if (line.find("zlo zhi") != std::string::npos) w >> lo >> hi, L[2] = hi;
    if (line.rfind("Atoms", 0) == 0) break;
  }
  double id, type, diameter, density;
  ParticleSpec p;
  while (in >> id >> type >> diameter >> density >> p.x[0] >> p.x[1] >> p.x[2]) {
    p.radius = 0.5 * diameter;
    p.gid = static_cast<std::int64_t>(id) - 1;
    ps.push_back(p);
  }
  System s(box_config(L, 5e7, 0.3, 5e-6, 1.25e-3), comm);
  s.add_particles(ps);
  return s;
}

void time_steps(benchmark::State& state, System& s, const Communicator& comm, bool phases) {
  for (int i = 0; i < 20; ++i) s.step();  // lists built, contacts formed
  s.set_profiling(phases);
  const DemTimers before = s.timers();
  const int steps_per_iteration = 50;
  double seconds = 0;
  long long steps = 0;
  for (auto _ : state) {
    Kokkos::fence();
    MPI_Barrier(comm.get());
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < steps_per_iteration; ++i) s.step();
    Kokkos::fence();
    MPI_Barrier(comm.get());
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(t);
    seconds += t;
    steps += steps_per_iteration;
  }
  const double n = double(s.global_count());
  state.counters["particles"] = n;
  state.counters["particle_steps_per_s"] = benchmark::Counter(
      n * steps / seconds, benchmark::Counter::kDefaults, benchmark::Counter::OneK::kIs1000);
  state.counters["ranks"] = comm.size();
  state.counters["threads"] = amphora::kernels::DefaultExecSpace().concurrency();
  const DemTimers& t = s.timers();
  state.counters["rebuilds"] = double(t.rebuilds - before.rebuilds);
  // The workload: pair contacts (each counted once) and wall contacts per particle.
  const DemDiagnostics d = s.diagnostics();
  state.counters["contacts_per_particle"] = double(d.contacts) / n;
  state.counters["wall_contacts_per_particle"] = double(d.wall_contacts) / n;
  if (phases) {
    const double total = (t.integrate - before.integrate) + (t.binning - before.binning) +
                         (t.list - before.list) + (t.force - before.force) + (t.comm - before.comm);
    state.counters["share_force"] = (t.force - before.force) / total;
    state.counters["share_list"] = (t.list - before.list) / total;
    state.counters["share_binning"] = (t.binning - before.binning) / total;
    state.counters["share_integrate"] = (t.integrate - before.integrate) / total;
    state.counters["share_comm"] = (t.comm - before.comm) / total;
  }
}

void run(benchmark::State& state, bool phases) {
  Communicator comm;
  System s = make_bed(state.range(0), comm);
  time_steps(state, s, comm, phases);
}

void DenseBed(benchmark::State& state) { run(state, false); }
void DenseBedPhases(benchmark::State& state) { run(state, true); }

void settled(benchmark::State& state, bool phases) {
  const char* path = std::getenv("AMPHORA_SETTLED_BED");
  if (!path) {
    state.SkipWithError("set AMPHORA_SETTLED_BED to a settled bed (scripts/bench_dem_settled.sh)");
    return;
  }
  Communicator comm;
  System s = read_bed(path, comm);
  time_steps(state, s, comm, phases);
}
void SettledBed(benchmark::State& state) { settled(state, false); }
void SettledBedPhases(benchmark::State& state) { settled(state, true); }

}  // namespace

BENCHMARK(DenseBed)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Iterations(4);
// Steps 21-220, as perf/liggghts/settled_bed.in times them.
BENCHMARK(SettledBed)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(4);
BENCHMARK(SettledBedPhases)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(DenseBedPhases)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Iterations(2);
