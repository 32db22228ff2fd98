#pragma once
// Deterministic loops over the pairs of a half Verlet list, templated on the pair law (the
// Cabana way: the application writes the law, the library the loop). Each pair is evaluated
// in its own orientation, smaller key (global id) first, so every rank and thread sees the
// same bits; a particle receives its pair contributions in an order set by the particles
// alone, so sums do not depend on threads, ranks or storage order.
//
// Two schedules of the same sums (up to round-off):
// - by slabs (host spaces): the row of a pair's first particle evaluates it once, keeps the
//   pair's state, adds its share to its particle and the partner's to the partner; rows run in
//   a SlabSchedule (slabs of one colour in parallel, no atomics);
// - by particle (devices): one work item per particle sums all its pairs, each evaluated by
//   both particles in the orientation of the smaller key; pair states are read from one buffer
//   and written to another (the law's), so again no atomics.
//
// A pair law provides (all KOKKOS_INLINE_FUNCTION, const):
//   Particle load(int i)              what a row reads of its particle (members x[3], r);
//   void body(int i, const Particle&, Sum&)   one-body terms (gravity, walls) into a zero Sum;
//   State state(int k); void set_state(int k, const State&)   the pair state of entry k (read
//                                     and written buffers; State{} is "no contact");
//   void prefetch(int k0, int k1)     hint: entries k0 .. k1 are next (may do nothing);
//   Effect interact(const Particle& a, int b, double rb, const double dx[3], double d2,
//                   double rsum, State& s)   the touching pair (a, b), dx = x_b - x_a;
//   void add_first(const Effect&, const Particle& a, Sum&)   its share on a;
//   void add_second(const Effect&, double rb, Sum&)          its share on b, into a Sum;
//   void add_second_to(int b, const Effect&, double rb)      the same, into b's arrays;
//   void add(int i, const Sum&); void store(int i, const Sum&)   a row's sum, added or stored.
#include <cstdint>

#include "kernels/particles/rows3.hpp"
#include "kernels/particles/slab_schedule.hpp"

namespace amphora::kernels::particles {

/// A full Verlet list (rows sorted by key) with each row split at its own pairs: row i's
/// partners of larger key are entries half(i) .. offsets(i + 1).
template <class Mem>
struct HalfPairList {
  using R = Kokkos::MemoryTraits<Kokkos::Restrict>;
  Kokkos::View<const int*, Mem, R> offsets, neighbors, half;
};

/// Sphere centres and radii, the geometry the loops test pairs with (|dx| < r_a + r_b).
template <class Mem>
struct Spheres {
  Rows3<const double> x;
  Kokkos::View<const double*, Mem, Kokkos::MemoryTraits<Kokkos::Restrict>> r;
};

/// The entry of row j (from half(j) on: its partners of larger key, sorted) holding key g.
template <class List, class Keys>
KOKKOS_INLINE_FUNCTION int own_entry(const List& L, const Keys& key, int j, std::int64_t g) {
  int lo = L.half(j), hi = L.offsets(j + 1);
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (key(L.neighbors(mid)) < g)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

/// The slab schedule: rows of owned particles (i < n_owned) and of ghosts (only their pairs
/// with owned particles). live(i) bit b: entry half(i) + b may hold a non-zero state (rows
/// with more than 32 own pairs keep their tail always "set"); it spares the loop the state
/// traffic of the many listed neighbours that do not touch, and is kept up to date here.
template <class ExecSpace, class Law>
void pair_sums_by_slabs(const ExecSpace& exec,
                        const SlabSchedule<typename ExecSpace::memory_space>& S,
                        const HalfPairList<typename ExecSpace::memory_space>& L,
                        const Spheres<typename ExecSpace::memory_space>& G, int n_owned,
                        const Kokkos::View<unsigned*, typename ExecSpace::memory_space>& live,
                        const Law& law) {
  using Mem = typename ExecSpace::memory_space;
  using R = Kokkos::MemoryTraits<Kokkos::Restrict>;
  const Kokkos::View<const int*, Mem, R> order = S.order, slab = S.start;
  const Kokkos::View<unsigned*, Mem, R> mask = live;
  const auto off = L.offsets, half = L.half, nbr = L.neighbors;
  const auto x = G.x;
  const auto rad = G.r;
  const int n = n_owned;
  for (int colour = 0; colour < 2; ++colour) {
    // Slabs hold unequal numbers of rows: one at a time to whichever thread is free.
    using Slabs =
        Kokkos::RangePolicy<ExecSpace, Kokkos::Schedule<Kokkos::Dynamic>, Kokkos::IndexType<int>>;
    Kokkos::parallel_for(
        "amphora::particles::pair_sums_by_slabs",
        Slabs(exec, S.colour_slabs[colour], S.colour_slabs[colour + 1], Kokkos::ChunkSize(1)),
        KOKKOS_LAMBDA(int u) {
          for (int a = slab(u); a < slab(u + 1); ++a) {
            if (a + 4 < slab(u + 1)) {  // the states of a row a few ahead
              const int r = order(a + 4);
              law.prefetch(half(r), off(r + 1));
            }
            const int i = order(a);
            const bool owned = i < n;  // else a ghost's row: only its pairs with owned particles
            const typename Law::Particle pi = law.load(i);
            typename Law::Sum sum{};
            if (owned) law.body(i, pi, sum);
            const int k0 = half(i);
            unsigned states = mask(i);
            for (int k = half(i); k < off(i + 1); ++k) {
              const int j = nbr(k);
              if (!owned && j >= n) continue;
              const double dx[3] = {x(j, 0) - pi.x[0], x(j, 1) - pi.x[1], x(j, 2) - pi.x[2]};
              const double d2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
              const double rj = rad(j), rsum = pi.r + rj;
              const unsigned bit = k - k0 < 32 ? 1u << (k - k0) : 0u;
              if (d2 >= rsum * rsum) {  // apart: the pair's state resets, where it may be set
                if (bit == 0u || (states & bit)) {
                  law.set_state(k, typename Law::State{});
                  states &= ~bit;
                }
                continue;
              }
              states |= bit;
              typename Law::State s = law.state(k);
              const auto e = law.interact(pi, j, rj, dx, d2, rsum, s);
              law.set_state(k, s);
              law.add_first(e, pi, sum);
              if (j < n) law.add_second_to(j, e, rj);
            }
            mask(i) = states;
            if (owned) law.add(i, sum);
          }
        });
  }
}

/// The particle schedule: one work item per row (owned particles and ghosts, `total` in all);
/// every entry's state is read through law.state and written through law.set_state (other
/// buffers: the caller swaps them after). A ghost's row only advances its states with owned
/// partners; an owned row stores its particle's whole sum.
template <class ExecSpace, class Law, class Keys>
void pair_sums_by_particle(const ExecSpace& exec,
                           const HalfPairList<typename ExecSpace::memory_space>& L,
                           const Spheres<typename ExecSpace::memory_space>& G, const Keys& key,
                           int n_owned, int total, const Law& law) {
  const auto off = L.offsets, half = L.half, nbr = L.neighbors;
  const auto x = G.x;
  const auto rad = G.r;
  const int n = n_owned;
  Kokkos::parallel_for(
      "amphora::particles::pair_sums_by_particle", RangePolicy<ExecSpace>(exec, 0, total),
      KOKKOS_LAMBDA(int i) {
        const bool owned = i < n;
        const typename Law::Particle pi = law.load(i);
        typename Law::Sum sum{};
        if (owned) law.body(i, pi, sum);
        // partners of larger key: the row's own pairs and states
        for (int k = half(i); k < off(i + 1); ++k) {
          const int j = nbr(k);
          typename Law::State s = law.state(k);
          if (owned || j < n) {
            const double dx[3] = {x(j, 0) - pi.x[0], x(j, 1) - pi.x[1], x(j, 2) - pi.x[2]};
            const double d2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
            const double rj = rad(j), rsum = pi.r + rj;
            if (d2 >= rsum * rsum) {
              s = typename Law::State{};  // apart: the state resets
            } else {
              const auto e = law.interact(pi, j, rj, dx, d2, rsum, s);
              law.add_first(e, pi, sum);
            }
          }
          law.set_state(k, s);
        }
        if (!owned) return;
        // partners of smaller key: the pair in the partner's orientation, from its state
        for (int k = off(i); k < half(i); ++k) {
          const int j = nbr(k);
          const double xj[3] = {x(j, 0), x(j, 1), x(j, 2)};
          const double dx[3] = {pi.x[0] - xj[0], pi.x[1] - xj[1], pi.x[2] - xj[2]};
          const double d2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
          const double rj = rad(j), rsum = rj + pi.r;
          if (d2 >= rsum * rsum) continue;
          typename Law::State s = law.state(own_entry(L, key, j, key(i)));
          const typename Law::Particle pj = law.load(j);
          const auto e = law.interact(pj, i, pi.r, dx, d2, rsum, s);
          law.add_second(e, pi.r, sum);
        }
        law.store(i, sum);
      });
}

}  // namespace amphora::kernels::particles
