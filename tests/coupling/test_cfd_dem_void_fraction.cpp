// The particle-centred void fraction with L2-projection smoothing (coupling/cfd_dem): it holds
// the particles' volume exactly, is uniform where the particles are, moves continuously with
// them, and the point basis it deposits with interpolates Q_k fields exactly.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "coupling/cfd_dem/void_fraction.hpp"
#include "test_backend.hpp"

namespace amphora::coupling::cfd_dem {
namespace {

using Exec = test::TestExecSpace;
using Fraction = VoidFraction<3, Exec>;
using Space = mesh::hex::QkSpace<3, Exec>;
using mesh::hex::FaceCondition;

mesh::hex::StructuredHexMesh<3> box(int cells, bool periodic_z) {
  mesh::hex::StructuredHexMesh<3> m;
  m.cells = {cells, cells, cells};
  m.upper = {1.0, 1.0, 1.0};
  for (int f = 0; f < 6; ++f) {
    m.faces[f] = (f < 4 || periodic_z) ? FaceCondition::periodic : FaceCondition::dirichlet;
  }
  return m;
}

struct Particles {
  Fraction::Points x;
  Fraction::Vector radius;
  double volume = 0.0;
};

/// n particles of radius r at the given centres (host vector of 3 n coordinates).
Particles particles(const std::vector<double>& centres, double r) {
  const int n = int(centres.size() / 3);
  Particles p{Fraction::Points("x", n), Fraction::Vector("r", n)};
  auto xh = Kokkos::create_mirror_view(p.x);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) xh(i, d) = centres[3 * i + d];
  }
  Kokkos::deep_copy(p.x, xh);
  Kokkos::deep_copy(p.radius, r);
  p.volume = n * 4.0 / 3.0 * M_PI * r * r * r;
  return p;
}

std::vector<double> random_centres(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> c(3 * n);
  for (double& v : c) v = u(gen);
  return c;
}

std::vector<double> host(const Fraction::Vector& v) {
  auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), v);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}

VoidFractionOptions pcm(double length) {
  VoidFractionOptions o;
  o.smoothing_length = length;
  return o;
}

VoidFractionOptions qcm(double length) {
  VoidFractionOptions o = pcm(length);
  o.method = VoidFractionMethod::qcm;
  return o;
}

TEST(VoidFraction, HoldsTheParticlesVolume) {
  for (int degree : {1, 2, 3}) {
    for (bool periodic_z : {true, false}) {
      const Space space(box(4, periodic_z), degree);
      for (const auto& options : {pcm(0.0), pcm(0.12), qcm(0.0), qcm(0.12)}) {
        const Fraction fraction(space, options);
        const Particles p = particles(random_centres(60, 7), 0.03);
        Fraction::Vector eps("eps", space.n_dofs());
        const auto result = fraction.compute(Exec(), p.x, p.radius, 60, eps);
        ASSERT_TRUE(result.converged) << result.final_residual;
        const double solid = 1.0 - fraction.integral(Exec(), eps);  // the box's volume is 1
        EXPECT_NEAR(solid / p.volume, 1.0, 1e-10)
            << "k " << degree << " periodic z " << periodic_z << " L " << options.smoothing_length
            << " qcm " << (options.method == VoidFractionMethod::qcm);
      }
    }
  }
}

TEST(VoidFraction, OneParticlePerCellIsUniformOnQ1) {
  // Q1, periodic: a particle at each cell centre gives every node 1/8 of eight particles (PCM),
  // or every node the same share by symmetry (QCM), so the right-hand side is
  // (1 - V_p / V_cell) M 1 and eps = 1 - V_p / V_cell exactly.
  const int n = 4;
  const Space space(box(n, true), 1);
  std::vector<double> c;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) c.insert(c.end(), {(i + 0.5) / n, (j + 0.5) / n, (k + 0.5) / n});
  const Particles p = particles(c, 0.08);
  const double expected = 1.0 - p.volume;  // V_p / V_cell: the total over the unit box
  for (const auto& options : {pcm(0.0), pcm(0.3), qcm(0.0), qcm(0.3)}) {
    const Fraction fraction(space, options);
    Fraction::Vector eps("eps", space.n_dofs());
    fraction.compute(Exec(), p.x, p.radius, n * n * n, eps);
    for (double e : host(eps)) EXPECT_NEAR(e, expected, 1e-11);
  }
}

TEST(VoidFraction, MovesContinuouslyWithTheParticles) {
  // A particle crossing a cell face changes eps by O(displacement): halving the move halves
  // the change (a cell-wise count would jump by V_p / V_cell).
  const Space space(box(4, false), 2);
  for (const auto& options : {pcm(0.1), qcm(0.0)}) {
    const Fraction fraction(space, options);
    auto change = [&](double delta) {
      const Particles a = particles({0.5 - 0.5 * delta, 0.4, 0.6}, 0.04);
      const Particles b = particles({0.5 + 0.5 * delta, 0.4, 0.6}, 0.04);  // x = 0.5: a face
      Fraction::Vector ea("ea", space.n_dofs()), eb("eb", space.n_dofs());
      fraction.compute(Exec(), a.x, a.radius, 1, ea);
      fraction.compute(Exec(), b.x, b.radius, 1, eb);
      const auto ha = host(ea), hb = host(eb);
      double m = 0.0;
      for (std::size_t i = 0; i < ha.size(); ++i) m = std::max(m, std::abs(ha[i] - hb[i]));
      return m;
    };
    const double c1 = change(1e-3), c2 = change(5e-4);
    EXPECT_LT(c1, 0.05 * 4.0 / 3.0 * M_PI * std::pow(0.04, 3) / std::pow(0.25, 3));
    EXPECT_NEAR(c1 / c2, 2.0, 0.05);
  }
}

VoidFractionOptions bounded(VoidFractionOptions o) {
  o.bounded = true;  // [0.36, 1]
  return o;
}

/// g = A eps - b over the lumped mass (a value of eps): the bounded problem's multiplier.
std::vector<double> multiplier(const Fraction& fraction, const Particles& p, int n,
                               const Fraction::Vector& eps) {
  const long dofs = fraction.basis_integrals().extent(0);
  Fraction::Vector b("b", dofs), g("g", dofs);
  fraction.deposit(Exec(), p.x, p.radius, n, b);
  kernels::blas1::axpy(Exec(), 1.0, fraction.basis_integrals(), b);
  fraction.apply(Exec(), eps, g);
  kernels::blas1::axpy(Exec(), -1.0, b, g);
  auto m = host(g);
  const auto mass = host(fraction.basis_integrals());
  for (std::size_t i = 0; i < m.size(); ++i) m[i] /= mass[i];
  return m;
}

TEST(VoidFraction, BoundedMeetsTheOptimalityConditions) {
  // 40 particles crowded into a cube of 0.2: unbounded, eps falls far below 0.36 there (and
  // rises over 1 beside it on Q2 without smoothing). Bounded, eps is the constrained
  // minimiser: within [0.36, 1], the multiplier zero where eps is free, >= 0 at the lower
  // bound, <= 0 at the upper. (PCM: the test forms its right-hand side from the deposit.)
  auto c = random_centres(40, 3);
  for (double& v : c) v = 0.4 + 0.2 * v;
  const Particles p = particles(c, 0.06);
  for (int degree : {1, 2}) {
    const Space space(box(4, false), degree);
    for (const auto& options : {pcm(0.0), pcm(0.12)}) {
      const Fraction plain(space, options), fraction(space, bounded(options));
      Fraction::Vector free("free", space.n_dofs()), eps("eps", space.n_dofs());
      ASSERT_TRUE(plain.compute(Exec(), p.x, p.radius, 40, free).converged);
      const auto result = fraction.compute(Exec(), p.x, p.radius, 40, eps);
      ASSERT_TRUE(result.converged) << fraction.bounds().iterations;
      const auto hf = host(free), he = host(eps);
      ASSERT_LT(*std::min_element(hf.begin(), hf.end()), 0.36);
      EXPECT_GT(fraction.bounds().at_lower, 0);
      const auto m = multiplier(fraction, p, 40, eps);
      for (std::size_t i = 0; i < he.size(); ++i) {
        const std::string where = "k " + std::to_string(degree) + " node " + std::to_string(i);
        EXPECT_GE(he[i], 0.36 - 1e-12) << where;
        EXPECT_LE(he[i], 1.0 + 1e-12) << where;
        if (he[i] == 0.36)
          EXPECT_GE(m[i], -1e-9) << where;
        else if (he[i] == 1.0)
          EXPECT_LE(m[i], 1e-9) << where;
        else
          EXPECT_NEAR(m[i], 0.0, 1e-9) << where;
      }
    }
  }
}

TEST(VoidFraction, BoundedIsTheUnboundedWhereNoBoundBinds) {
  const Space space(box(4, true), 1);
  const Particles p = particles(random_centres(60, 7), 0.03);
  const Fraction plain(space, pcm(0.12)), fraction(space, bounded(pcm(0.12)));
  Fraction::Vector free("free", space.n_dofs()), eps("eps", space.n_dofs());
  plain.compute(Exec(), p.x, p.radius, 60, free);
  ASSERT_TRUE(fraction.compute(Exec(), p.x, p.radius, 60, eps).converged);
  const auto hf = host(free);
  ASSERT_GT(*std::min_element(hf.begin(), hf.end()), 0.36);
  ASSERT_LE(*std::max_element(hf.begin(), hf.end()), 1.0);
  EXPECT_EQ(fraction.bounds().iterations, 0);
  // The bounded path keeps CG's eps. The two solves deposit their right-hand sides with
  // atomics, so on threads they differ in round-off (a few ulps of 1 measured), not bit for bit.
  const auto he = host(eps);
  for (std::size_t i = 0; i < he.size(); ++i) EXPECT_NEAR(he[i], hf[i], 1e-13) << "node " << i;
}

TEST(VoidFraction, BoundsOutOfOrderAreRefused) {
  const Space space(box(2, false), 1);
  VoidFractionOptions o = bounded(pcm(0.1));
  o.lower_bound = 0.5, o.upper_bound = 0.4;
  EXPECT_THROW(Fraction(space, o), std::invalid_argument);
  o.lower_bound = 0.0, o.upper_bound = 1.0;
  EXPECT_THROW(Fraction(space, o), std::invalid_argument);
}

TEST(ParticleMesh, InterpolatesQkFieldsAndGradientsExactly) {
  // f = x^2 y - 3 z^2 + x y z lies in Q_2: its nodal interpolant and its gradient evaluated
  // anywhere are f's.
  auto m = box(3, false);
  for (auto& face : m.faces) face = FaceCondition::dirichlet;  // f is not periodic
  const Space space(m, 2);
  const Fraction fraction(space, pcm(0.0));
  auto f = [](const mesh::hex::Point3& x, int) {
    return x[0] * x[0] * x[1] - 3 * x[2] * x[2] + x[0] * x[1] * x[2];
  };
  const std::vector<double> nodal = space.interpolate(f);
  Fraction::Vector fv("f", space.n_dofs());
  auto fh = Kokkos::create_mirror_view(fv);
  for (long i = 0; i < space.n_dofs(); ++i) fh(i) = nodal[i];
  Kokkos::deep_copy(fv, fh);
  const std::vector<double> c = random_centres(40, 3);
  const Particles p = particles(c, 0.01);
  Fraction::Vector out("out", 40);
  Fraction::Points grad("grad", 40);
  const Kokkos::View<double* [1], Kokkos::LayoutRight, Exec::memory_space> value("value", 40);
  interpolate(Exec(), fraction.basis(), fv, 1, p.x, 40, value);
  interpolate_gradient(Exec(), fraction.basis(), fv, p.x, 40, grad);
  auto gh = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), grad);
  Kokkos::deep_copy(out, Kokkos::subview(value, Kokkos::ALL, 0));
  const auto h = host(out);
  for (int i = 0; i < 40; ++i) {
    const double x = c[3 * i], y = c[3 * i + 1], z = c[3 * i + 2];
    EXPECT_NEAR(h[i], f({x, y, z}, 0), 1e-13) << i;
    EXPECT_NEAR(gh(i, 0), 2 * x * y + y * z, 1e-12) << i;
    EXPECT_NEAR(gh(i, 1), x * x + x * z, 1e-12) << i;
    EXPECT_NEAR(gh(i, 2), -6 * z + x * y, 1e-12) << i;
  }
}

TEST(ParticleMesh, InterpolatesCurlsExactly) {
  // u = (x y z, x^2 - z^2, x y^2) lies in Q_2 per component; curl u = (2 x y + 2 z, x y - y^2,
  // 2 x - x z).
  auto m = box(3, false);
  for (auto& face : m.faces) face = FaceCondition::dirichlet;
  const Space space(m, 2);
  const Fraction fraction(space, pcm(0.0));
  const std::vector<double> nodal = space.interpolate(
      [](const mesh::hex::Point3& x, int c) {
        return c == 0 ? x[0] * x[1] * x[2]
                      : (c == 1 ? x[0] * x[0] - x[2] * x[2] : x[0] * x[1] * x[1]);
      },
      3);
  Fraction::Vector u("u", nodal.size());
  auto uh = Kokkos::create_mirror_view(u);
  for (std::size_t i = 0; i < nodal.size(); ++i) uh(i) = nodal[i];
  Kokkos::deep_copy(u, uh);
  const std::vector<double> c = random_centres(40, 5);
  const Particles p = particles(c, 0.01);
  Fraction::Points curl("curl", 40);
  interpolate_curl(Exec(), fraction.basis(), u, p.x, 40, curl);
  auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), curl);
  for (int i = 0; i < 40; ++i) {
    const double x = c[3 * i], y = c[3 * i + 1], z = c[3 * i + 2];
    EXPECT_NEAR(h(i, 0), 2 * x * y + 2 * z, 1e-12) << i;
    EXPECT_NEAR(h(i, 1), x * y - y * y, 1e-12) << i;
    EXPECT_NEAR(h(i, 2), 2 * x - x * z, 1e-12) << i;
  }
}

TEST(ParticleMesh, InterpolatesLaplaciansExactly) {
  // Q2: f = x^2 y - 3 z^2 + x y z, lap f = 2 y - 6; Q3: g = x^3 - 2 y^2 z^3,
  // lap g = 6 x - 4 z^3 - 12 y^2 z. Both lie in their spaces, so the Laplacians of their
  // nodal interpolants anywhere are theirs. Q1: zero (linear along each direction).
  auto m = box(3, false);
  for (auto& face : m.faces) face = FaceCondition::dirichlet;
  const auto f2 = [](const mesh::hex::Point3& x, int) {
    return x[0] * x[0] * x[1] - 3 * x[2] * x[2] + x[0] * x[1] * x[2];
  };
  const auto f3 = [](const mesh::hex::Point3& x, int) {
    return x[0] * x[0] * x[0] - 2 * x[1] * x[1] * x[2] * x[2] * x[2];
  };
  for (int degree : {1, 2, 3}) {
    const Space space(m, degree);
    const Fraction fraction(space, pcm(0.0));
    const std::vector<double> nodal = degree == 3 ? space.interpolate(f3) : space.interpolate(f2);
    Fraction::Vector fv("f", space.n_dofs());
    auto fh = Kokkos::create_mirror_view(fv);
    for (long i = 0; i < space.n_dofs(); ++i) fh(i) = nodal[i];
    Kokkos::deep_copy(fv, fh);
    const std::vector<double> c = random_centres(40, 7);
    const Particles p = particles(c, 0.01);
    const Kokkos::View<double* [1], Kokkos::LayoutRight, Exec::memory_space> lap("lap", 40);
    interpolate_laplacian(Exec(), fraction.basis(), fv, 1, p.x, 40, lap);
    auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), lap);
    for (int i = 0; i < 40; ++i) {
      const double x = c[3 * i], y = c[3 * i + 1], z = c[3 * i + 2];
      const double exact = degree == 1   ? 0.0
                           : degree == 2 ? 2 * y - 6
                                         : 6 * x - 4 * z * z * z - 12 * y * y * z;
      EXPECT_NEAR(h(i, 0), exact, 1e-10) << "Q" << degree << " point " << i;
    }
  }
}

TEST(ParticleMesh, SpreadForcesSumToTheParticlesTotal) {
  // The fluid's share of the particles' forces, spread by the partition of unity, sums to what
  // the particles receive, per component, to round-off (Q2 and Q3, with periodic wraps).
  for (int degree : {2, 3}) {
    const Space space(box(4, false), degree);
    const Fraction fraction(space, pcm(0.0));
    const int n = 50;
    const Particles p = particles(random_centres(n, 11), 0.01);
    Fraction::Points F("F", n);
    auto fh = Kokkos::create_mirror_view(F);
    std::mt19937 gen(5);
    std::normal_distribution<double> normal(0.0, 1e-3);
    double total[3] = {0, 0, 0}, scale = 0.0;
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        fh(i, c) = normal(gen);
        total[c] += fh(i, c);
        scale += std::abs(fh(i, c));
      }
    Kokkos::deep_copy(F, fh);
    const long nd = space.n_dofs();
    Fraction::Vector b("b", 3 * nd);
    spread(Exec(), fraction.basis(), F, 3, p.x, n, b);
    const auto bh = host(b);
    for (int c = 0; c < 3; ++c) {
      double s = 0.0;
      for (long j = 0; j < nd; ++j) s += bh[c * nd + j];
      EXPECT_NEAR(s, total[c], 1e-14 * scale) << "k " << degree << " component " << c;
    }
  }
}

TEST(VoidFraction, QcmCountsAParticleThatDriftedPastAPeriodicFaceOnce) {
  // Between list rebuilds a DEM's owned particle drifts past a periodic face (here x = 1.02,
  // built at 0.99) and its ghost image (built at -0.01, now 0.02) into the box. The image is
  // told by where it was built: eps is the lone particle's at the wrapped place, volume held.
  const Space space(box(4, false), 2);
  const Fraction fraction(space, qcm(0.0));
  const Particles now = particles({1.02, 0.4, 0.6, 0.02, 0.4, 0.6}, 0.04);
  const Particles built = particles({0.99, 0.4, 0.6, -0.01, 0.4, 0.6}, 0.04);
  const Particles alone = particles({0.02, 0.4, 0.6}, 0.04);
  Fraction::Vector eps("eps", space.n_dofs()), lone("lone", space.n_dofs());
  ASSERT_TRUE(fraction.compute(Exec(), now.x, now.radius, 1, eps, 2, {true, true, true}, built.x)
                  .converged);
  ASSERT_TRUE(fraction.compute(Exec(), alone.x, alone.radius, 1, lone).converged);
  EXPECT_NEAR((1.0 - fraction.integral(Exec(), eps)) / alone.volume, 1.0, 1e-10);
  const auto he = host(eps), hl = host(lone);
  for (std::size_t i = 0; i < he.size(); ++i) EXPECT_NEAR(he[i], hl[i], 1e-12) << i;
}

TEST(VoidFraction, QcmSpheresThatMissAParticleAreRefused) {
  // Reference spheres of radius 0.01 on cells of 0.25 miss a particle between the Gauss
  // points: its volume would be lost, so the computation stops and says what to change.
  const Space space(box(4, false), 1);
  VoidFractionOptions o = qcm(0.0);
  o.qcm_radius = 0.01;
  const Fraction fraction(space, o);
  const Particles p = particles({0.125, 0.125, 0.125}, 0.005);  // a cell centre
  Fraction::Vector eps("eps", space.n_dofs());
  EXPECT_THROW(fraction.compute(Exec(), p.x, p.radius, 1, eps), std::runtime_error);
}

TEST(VoidFraction, CurvedCellsAreRefused) {
  auto m = box(2, false);
  m.deformation = [](const mesh::hex::Point3& x) { return x; };
  const Space space(m, 1);
  EXPECT_THROW(Fraction(space, pcm(0.1)), std::invalid_argument);
}

}  // namespace
}  // namespace amphora::coupling::cfd_dem
