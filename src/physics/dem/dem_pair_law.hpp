#pragma once
// The DEM's pair law for the particle library's pair loops (kernels/particles/pair_loop.hpp):
// Hertz–Mindlin contacts with a tangential spring per pair (the pair state), gravity and the
// walls as one-body terms (with a spring per particle and wall). The loops own the schedule;
// this file owns the physics at a pair.
#include "kernels/particles/rows3.hpp"
#include "kernels/prefetch.hpp"
#include "physics/dem/hertz_mindlin.hpp"
#include "physics/dem/walls.hpp"

namespace amphora::physics::dem {

using kernels::particles::Rows3;

/// Gravity and the walls' forces on particle i at (x, v, omega) and time t, where the share
/// its row adds starts. Walls not in `near` are skipped.
template <class Mem>
struct BodyForces {
  using R = Kokkos::MemoryTraits<Kokkos::Restrict>;
  Kokkos::View<const double*, Mem, R> rad, mass;
  Kokkos::View<const int*, Mem, R> mat;
  Kokkos::View<const PairCoefficients**, Mem, R> pairs;
  Kokkos::View<const Wall*, Mem, R> walls;
  Kokkos::View<double** [3], Kokkos::LayoutRight, Mem, R> wshear;
  Kokkos::View<unsigned*, Mem, R> wmask;
  int nw;
  double dt, g[3];

  KOKKOS_FORCEINLINE_FUNCTION void operator()(int i, double t, unsigned near, const double xi[3],
                                              const double vi[3], const double wi[3], double F[3],
                                              double T[3]) const {
    const double ri = rad(i), mi = mass(i);
    for (int d = 0; d < 3; ++d) {
      F[d] = mi * g[d];
      T[d] = 0.0;
    }
    if (!near) return;
    for (int w = 0; w < nw; ++w) {
      if (!(near & (1u << w))) continue;
      double nn[3], delta, vw[3];
      const Wall& wall = walls(w);
      if (!wall_contact(wall, t, xi, ri, nn, delta, vw)) {
        if (wmask(i) & (1u << w)) {
          wmask(i) &= ~(1u << w);
          wshear(i, w, 0) = wshear(i, w, 1) = wshear(i, w, 2) = 0.0;
        }
        continue;
      }
      wmask(i) |= 1u << w;
      const double vr[3] = {vi[0] - vw[0] + ri * (wi[1] * nn[2] - wi[2] * nn[1]),
                            vi[1] - vw[1] + ri * (wi[2] * nn[0] - wi[0] * nn[2]),
                            vi[2] - vw[2] + ri * (wi[0] * nn[1] - wi[1] * nn[0])};
      const double wr[3] = {wi[0] - wall.angular_velocity[0], wi[1] - wall.angular_velocity[1],
                            wi[2] - wall.angular_velocity[2]};
      double s[3] = {wshear(i, w, 0), wshear(i, w, 1), wshear(i, w, 2)};
      const ContactForce c =
          hertz_mindlin_force(pairs(mat(i), wall.material), ri, mi, nn, delta, vr, wr, dt, s);
      for (int d = 0; d < 3; ++d) {
        wshear(i, w, d) = s[d];
        F[d] += c.force[d];
        T[d] += ri * c.moment[d] + c.rolling[d];
      }
    }
  }
};

/// The Hertz–Mindlin contact of particle a with a touching partner b of larger gid, in a's
/// orientation: dx = x_b - x_a, d2 = |dx|^2 < rsum^2; s, the pair's spring, is advanced.
/// Returns the force and moments on a.
template <class Mem>
struct PairContact {
  using R = Kokkos::MemoryTraits<Kokkos::Restrict>;
  Rows3<const double> v, om;
  Kokkos::View<const double*, Mem, R> mass;
  Kokkos::View<const int*, Mem, R> mat;
  Kokkos::View<const PairCoefficients**, Mem, R> pairs;
  double dt;

  KOKKOS_FORCEINLINE_FUNCTION ContactForce operator()(int j, double ri, double rj, double mi,
                                                      int mati, const double vi[3],
                                                      const double wi[3], const double dx[3],
                                                      double d2, double rsum, double s[3]) const {
    const double dist = kernels::math::sqrt(d2);
    const double inv = 1.0 / dist;
    const double nn[3] = {dx[0] * inv, dx[1] * inv, dx[2] * inv};
    const double mj = mass(j);
    const double dv[3] = {vi[0] - v(j, 0), vi[1] - v(j, 1), vi[2] - v(j, 2)};
    // The approach speed from dx, not n: off the chain sqrt -> division -> n.
    const double vn = (dv[0] * dx[0] + dv[1] * dx[1] + dv[2] * dx[2]) * inv;
    // R* = ri rj / (ri + rj) and m* = mi mj / (mi + mj) with one division.
    const double q = 1.0 / (rsum * (mi + mj));
    // Velocity of i's contact point relative to j's: v_i - v_j + (r_i w_i + r_j w_j) x n.
    const double w[3] = {ri * wi[0] + rj * om(j, 0), ri * wi[1] + rj * om(j, 1),
                         ri * wi[2] + rj * om(j, 2)};
    const double vr[3] = {dv[0] + w[1] * nn[2] - w[2] * nn[1], dv[1] + w[2] * nn[0] - w[0] * nn[2],
                          dv[2] + w[0] * nn[1] - w[1] * nn[0]};
    const double wr[3] = {wi[0] - om(j, 0), wi[1] - om(j, 1), wi[2] - om(j, 2)};
    return hertz_mindlin_force(pairs(mati, mat(j)), ri * rj * (mi + mj) * q, mi * mj * rsum * q, nn,
                               rsum - dist, vn, vr, wr, dt, s);
  }
};

/// The pair law of the DEM for kernels::particles' pair loops: a particle's state as a row
/// reads it, the force and torque it sums, the spring of a pair as its state.
template <class Mem>
struct HertzMindlinPairLaw {
  struct Particle {
    double x[3], v[3], w[3], r, m;
    int mat;
  };
  struct Sum {
    double F[3], T[3];
  };
  struct State {
    double s[3];
  };

  Rows3<const double> x, v, om;
  Rows3<double> f, tq;
  Rows3<const double> spring_in;
  Rows3<double> spring_out;  ///< the same buffer as spring_in for the slab schedule
  Kokkos::View<const double*, Mem, Kokkos::MemoryTraits<Kokkos::Restrict>> rad, mass;
  Kokkos::View<const int*, Mem, Kokkos::MemoryTraits<Kokkos::Restrict>> mat;
  Kokkos::View<const unsigned*, Mem, Kokkos::MemoryTraits<Kokkos::Restrict>> wall_near;
  BodyForces<Mem> body_forces;
  PairContact<Mem> contact;
  double t;

  KOKKOS_FORCEINLINE_FUNCTION Particle load(int i) const {
    return {{x(i, 0), x(i, 1), x(i, 2)},
            {v(i, 0), v(i, 1), v(i, 2)},
            {om(i, 0), om(i, 1), om(i, 2)},
            rad(i),
            mass(i),
            mat(i)};
  }
  KOKKOS_FORCEINLINE_FUNCTION void body(int i, const Particle& p, Sum& s) const {
    body_forces(i, t, wall_near(i), p.x, p.v, p.w, s.F, s.T);
  }
  KOKKOS_FORCEINLINE_FUNCTION State state(int k) const {
    return {{spring_in(k, 0), spring_in(k, 1), spring_in(k, 2)}};
  }
  KOKKOS_FORCEINLINE_FUNCTION void set_state(int k, const State& s) const {
    for (int d = 0; d < 3; ++d) spring_out(k, d) = s.s[d];
  }
  /// The springs of a row about to run: their lines are far apart and read only where pairs
  /// touch, which no hardware prefetcher foresees.
  KOKKOS_FORCEINLINE_FUNCTION void prefetch(int k0, int k1) const {
    const double* p = spring_out.p + 3 * size_t(k0);
    if (k0 < k1) kernels::prefetch_line(p, true);
    if (k0 + 1 < k1) kernels::prefetch_line(p + 5, true);
  }
  KOKKOS_FORCEINLINE_FUNCTION ContactForce interact(const Particle& a, int b, double rb,
                                                    const double dx[3], double d2, double rsum,
                                                    State& s) const {
    return contact(b, a.r, rb, a.m, a.mat, a.v, a.w, dx, d2, rsum, s.s);
  }
  KOKKOS_FORCEINLINE_FUNCTION void add_first(const ContactForce& c, const Particle& a,
                                             Sum& s) const {
    for (int d = 0; d < 3; ++d) {
      s.F[d] += c.force[d];
      s.T[d] += a.r * c.moment[d] + c.rolling[d];
    }
  }
  KOKKOS_FORCEINLINE_FUNCTION void add_second(const ContactForce& c, double rb, Sum& s) const {
    for (int d = 0; d < 3; ++d) {
      s.F[d] -= c.force[d];
      s.T[d] += rb * c.moment[d] - c.rolling[d];
    }
  }
  KOKKOS_FORCEINLINE_FUNCTION void add_second_to(int b, const ContactForce& c, double rb) const {
    for (int d = 0; d < 3; ++d) {
      f(b, d) -= c.force[d];
      tq(b, d) += rb * c.moment[d] - c.rolling[d];
    }
  }
  KOKKOS_FORCEINLINE_FUNCTION void add(int i, const Sum& s) const {
    for (int d = 0; d < 3; ++d) {
      f(i, d) += s.F[d];
      tq(i, d) += s.T[d];
    }
  }
  KOKKOS_FORCEINLINE_FUNCTION void store(int i, const Sum& s) const {
    for (int d = 0; d < 3; ++d) {
      f(i, d) = s.F[d];
      tq(i, d) = s.T[d];
    }
  }
};

}  // namespace amphora::physics::dem
