// DEM throughput on a dense bed of monodisperse glass beads (simple-cubic lattice of touching
// 3 mm spheres in a walled box, under gravity): particle-steps per second, and the share of
// time in integration, binning, list build, force and communication. The same system as
// perf/liggghts/dense_bed.in, so the two can be compared on one machine (scripts/bench_dem.sh).
// Run at 1 and 2 threads (OMP_NUM_THREADS) and 1 and 2 ranks (mpiexec -n 2).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

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

System make_bed(long n, const Communicator& comm) {
  int nx, ny, nz;
  bed_shape(n, nx, ny, nz);
  Material glass;
  glass.density = 2500;
  glass.youngs_modulus = 5e6;
  glass.poisson_ratio = 0.3;
  glass.restitution = 0.9;
  glass.friction = 0.5;
  DemConfig c;
  c.materials = {glass};
  c.gravity = {0, 0, -9.81};
  c.dt = 1e-5;
  c.max_radius = 0.5 * kD;
  c.skin = 0.25 * kD;
  const double L[3] = {nx * kD, ny * kD, (nz + 2) * kD};
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
  System s(c, comm);
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

void run(benchmark::State& state, bool phases) {
  Communicator comm;
  System s = make_bed(state.range(0), comm);
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

void DenseBed(benchmark::State& state) { run(state, false); }
void DenseBedPhases(benchmark::State& state) { run(state, true); }

}  // namespace

BENCHMARK(DenseBed)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Iterations(4);
BENCHMARK(DenseBedPhases)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Iterations(2);
