// The tall-cell velocity kernels (Irving et al. 2006): the momentum-conserving linear fit that
// transfers velocity onto a rebuilt tall-cell grid, and the conservative upwind advection inside
// tall cells: momentum kept to round-off, linear fields fitted and translated exactly. Speeds
// read from the ends of linear rows equal those of every row, and the level-set kernels started
// at a first row equal the whole-lattice ones above it.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "kernels/host_vector.hpp"
#include "kernels/mac/tall_cell_advection.hpp"
#include "test_backend.hpp"

namespace amphora::kernels::mac {
namespace {

using Exec = test::TestExecSpace;
using Mem = test::TestMemSpace;
using kernels::mac::MacGrid;

/// Columns with the given per-column terrain and band rows.
template <class M = Mem>
kernels::mac::TallCellColumns<M> columns(const MacGrid& g, const std::vector<int>& terrain,
                                         const std::vector<int>& band) {
  kernels::mac::TallCellColumns<M> T(g);
  std::vector<int> t(T.terrain.extent(0), 0),
      b(T.band.extent(0), 0);  // the ghost ring: no tall cells
  for (int k = 0; k < g.nz; ++k)
    for (int i = 0; i < g.nx; ++i) {
      t[T.column(i, k)] = terrain[i + g.nx * k];
      b[T.column(i, k)] = band[i + g.nx * k];
    }
  Kokkos::deep_copy(T.terrain, kernels::to_view<M>(t));
  Kokkos::deep_copy(T.band, kernels::to_view<M>(b));
  return T;
}

/// Uneven tall cells: terrain 0..2, band 5..10 (some columns without a tall cell).
template <class M = Mem>
kernels::mac::TallCellColumns<M> uneven_columns(const MacGrid& g) {
  std::vector<int> terrain, band;
  for (int k = 0; k < g.nz; ++k)
    for (int i = 0; i < g.nx; ++i) {
      terrain.push_back((i + 2 * k) % 3);
      band.push_back((i * 7 + k * 3) % 5 == 0 ? terrain.back() : 5 + (i + k) % 6);
    }
  return columns<M>(g, terrain, band);
}

TEST(TallCellVelocity, LinearFitKeepsEachColumnsMomentumAndLinearProfiles) {
  const MacGrid g{9, 14, 7, 0.1, {0, 0, 0}};
  const auto T = uneven_columns(g);
  const auto th = uneven_columns<kernels::HostMemSpace>(g);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  long fitted = 0;
  for (int d = 0; d < 3; ++d) {
    std::vector<double> random(g.padded_size()), linear(g.padded_size());
    for (int k = 0; k < g.nz + 1; ++k)
      for (int j = 0; j < g.ny + 1; ++j)
        for (int i = 0; i < g.nx + 1; ++i) {
          random[g.index(i, j, k)] = U(rng);
          linear[g.index(i, j, k)] = 0.3 * i - 0.7 * k + (0.2 + 0.01 * i) * j;
        }
    auto rf = kernels::to_view<Mem>(random), lf = kernels::to_view<Mem>(linear);
    fit_linear_in_tall_cells(Exec(), T, d, rf);
    fit_linear_in_tall_cells(Exec(), T, d, lf);
    const auto r = kernels::to_std_vector(rf), l = kernels::to_std_vector(lf);
    for (int k = 0; k < g.nz + (d == 2); ++k)
      for (int i = 0; i < g.nx + (d == 0); ++i) {
        int lo, hi;
        th.tall_rows(d, i, k, lo, hi);
        double before = 0, after = 0;
        for (int j = 0; j < g.ny + (d == 1); ++j) {
          const int c = g.index(i, j, k);
          EXPECT_NEAR(l[c], linear[c], 1e-13) << "a linear profile is its own fit";
          if (j < lo || j >= hi) {
            EXPECT_EQ(r[c], random[c]) << "samples outside tall cells are kept";
            continue;
          }
          before += random[c], after += r[c];
          if (j >= lo + 2) {  // linear in height: second differences vanish
            const int sy = g.stride_y();
            EXPECT_NEAR(r[c] - 2 * r[c - sy] + r[c - 2 * sy], 0.0, 1e-13);
          }
        }
        EXPECT_NEAR(after, before, 1e-13 * (hi - lo + 1)) << "column momentum, d = " << d;
        fitted += hi - lo >= 3;
      }
  }
  EXPECT_GT(fitted, 60);  // the test sees many fitted columns
}

/// Random face samples of component d on g's lattice.
std::vector<double> random_faces(const MacGrid& g, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::vector<double> f(g.padded_size(), 0.0);
  for (int k = 0; k < g.nz + 1; ++k)
    for (int j = 0; j < g.ny + 1; ++j)
      for (int i = 0; i < g.nx + 1; ++i) f[g.index(i, j, k)] = U(rng);
  return f;
}

TEST(TallCellVelocity, FitSkipsOnlyTheColumnsWhoseTallRowsAreFitted) {
  // the grid moved: some columns' bands rose by one, some terrains by one
  const MacGrid g{9, 14, 7, 0.1, {0, 0, 0}};
  std::vector<int> terrain, band, old_terrain, old_band;
  for (int k = 0; k < g.nz; ++k)
    for (int i = 0; i < g.nx; ++i) {
      terrain.push_back((i + 2 * k) % 3);
      band.push_back(5 + (i + k) % 6);
      old_terrain.push_back(terrain.back() + ((i + k) % 7 == 0));
      old_band.push_back(band.back() + ((i * 3 + k) % 4 == 0));
    }
  const auto T = columns(g, terrain, band), old = columns(g, old_terrain, old_band);
  const auto th = columns<kernels::HostMemSpace>(g, terrain, band),
             oh = columns<kernels::HostMemSpace>(g, old_terrain, old_band);
  std::mt19937 rng(5);
  long skipped = 0, refitted = 0;
  for (int d = 0; d < 3; ++d) {
    const auto random = random_faces(g, rng);
    auto all = kernels::to_view<Mem>(random), changed = kernels::to_view<Mem>(random);
    fit_linear_in_tall_cells(Exec(), T, d, all);
    fit_linear_in_tall_cells(Exec(), T, d, changed, old);
    const auto a = kernels::to_std_vector(all), c = kernels::to_std_vector(changed);
    for (int k = 0; k < g.nz + (d == 2); ++k)
      for (int i = 0; i < g.nx + (d == 0); ++i) {
        int lo, hi, olo, ohi;
        th.tall_rows(d, i, k, lo, hi);
        oh.tall_rows(d, i, k, olo, ohi);
        const bool same = lo == olo && hi == ohi;
        for (int j = 0; j < g.ny + (d == 1); ++j) {
          const int m = g.index(i, j, k);
          if (same)
            EXPECT_EQ(c[m], random[m]) << "a column whose tall rows did not change is left alone";
          else
            EXPECT_EQ(c[m], a[m])
                << "a column whose tall rows changed is fitted as without `fitted`";
        }
        if (hi - lo >= 3) (same ? skipped : refitted) += 1;
      }
  }
  EXPECT_GT(skipped, 20);
  EXPECT_GT(refitted, 20);
}

TEST(TallCellVelocity, CourantSpeedFromTheEndsEqualsEveryRow) {
  // faces linear in their tall rows (fitted), random elsewhere: the largest |u| + |v| + |w| over
  // the tall cells, as read from the ends of linear rows, against every row. One column's six
  // faces at a time (the others zero), and the samples outside linear rows scaled up (a row
  // wrongly skipped holds the largest) or down (a wrongly read end is no bound), so a wrong row
  // in any column shows. Bands vary differently along x and z.
  const MacGrid g{9, 14, 7, 0.1, {0, 0, 0}};
  std::vector<int> terrain, band;
  for (int k = 0; k < g.nz; ++k)
    for (int i = 0; i < g.nx; ++i) {
      terrain.push_back((i + 2 * k) % 3);
      band.push_back(6 + (2 * i + 3 * k) % 7);
    }
  const auto T = columns(g, terrain, band);
  const auto th = columns<kernels::HostMemSpace>(g, terrain, band);
  std::mt19937 rng(11);
  std::vector<double> f[3];
  for (int d = 0; d < 3; ++d) {
    auto view = kernels::to_view<Mem>(random_faces(g, rng));
    fit_linear_in_tall_cells(Exec(), T, d, view);
    f[d] = kernels::to_std_vector(view);
  }
  const int sy = g.stride_y(), sz = g.stride_z();
  long skipping = 0;
  for (double scale : {10.0, 0.1})
    for (int k0 = 0; k0 < g.nz; ++k0)
      for (int i0 = 0; i0 < g.nx; ++i0) {
        std::vector<double> m[3];
        for (int d = 0; d < 3; ++d) {
          m[d].assign(g.padded_size(), 0.0);
          for (int s = 0; s < (d == 1 ? 1 : 2); ++s) {
            const int fi = i0 + (d == 0) * s, fk = k0 + (d == 2) * s;
            int lo, hi;
            th.tall_rows(d, fi, fk, lo, hi);
            for (int j = 0; j <= g.ny; ++j) {
              const int c = g.index(fi, j, fk);
              m[d][c] = f[d][c] * (j >= lo && j < hi ? 1.0 : scale);
            }
          }
        }
        double every_row = 0.0;
        for (int k = 0; k < g.nz; ++k)
          for (int i = 0; i < g.nx; ++i) {
            const int col = th.column(i, k);
            for (int j = th.terrain(col); j < th.band(col); ++j) {
              const int c = g.index(i, j, k);
              every_row =
                  std::max(every_row, std::max(std::abs(m[0][c]), std::abs(m[0][c + 1])) +
                                          std::max(std::abs(m[1][c]), std::abs(m[1][c + sy])) +
                                          std::max(std::abs(m[2][c]), std::abs(m[2][c + sz])));
            }
          }
        const double speed =
            tall_cell_speed(Exec(), T, kernels::to_view<Mem>(m[0]), kernels::to_view<Mem>(m[1]),
                            kernels::to_view<Mem>(m[2]));
        EXPECT_NEAR(speed, every_row, 1e-14 * every_row)
            << "column " << i0 << ", " << k0 << ", scale " << scale;
        const int col = th.column(i0, k0);
        skipping += th.band(col) - th.terrain(col) >= 6;
      }
  EXPECT_GT(skipping, 10);  // columns with rows the kernel need not read
  // no tall cell at all: no speed limit from them
  const auto uniform = columns(g, terrain, terrain);
  EXPECT_EQ(tall_cell_speed(Exec(), uniform, kernels::to_view<Mem>(f[0]),
                            kernels::to_view<Mem>(f[1]), kernels::to_view<Mem>(f[2])),
            0.0);
}

TEST(TallCellVelocity, MaxAbsFromTheEndsOfLinearRowsEqualsEveryRow) {
  // faces linear in their tall rows, random and ten times larger elsewhere (a row read outside
  // the tall rows would win): the largest |f| over the tall rows below `below`, read from the
  // ends, against every such row, for cuts below, inside and above the tall cells
  const MacGrid g{9, 14, 7, 0.1, {0, 0, 0}};
  const auto T = uneven_columns(g);
  const auto th = uneven_columns<kernels::HostMemSpace>(g);
  std::mt19937 rng(5);
  long cut = 0;
  for (int d = 0; d < 3; ++d) {
    auto view = kernels::to_view<Mem>(random_faces(g, rng));
    fit_linear_in_tall_cells(Exec(), T, d, view);
    auto f = kernels::to_std_vector(view);
    for (int k = 0; k < g.nz + (d == 2); ++k)
      for (int i = 0; i < g.nx + (d == 0); ++i) {
        int lo, hi;
        th.tall_rows(d, i, k, lo, hi);
        for (int j = 0; j <= g.ny; ++j)
          if (j < lo || j >= hi) f[g.index(i, j, k)] *= 10.0;
      }
    const auto scaled = kernels::to_view<Mem>(f);
    for (int below : {0, 3, 6, 8, 11, g.ny + 1}) {
      double every_row = 0.0;
      for (int k = 0; k < g.nz + (d == 2); ++k)
        for (int i = 0; i < g.nx + (d == 0); ++i) {
          int lo, hi;
          th.tall_rows(d, i, k, lo, hi);
          for (int j = lo; j < std::min(hi, below); ++j)
            every_row = std::max(every_row, std::abs(f[g.index(i, j, k)]));
          cut += lo < below && below < hi - 1;
        }
      EXPECT_EQ(tall_rows_max_abs(Exec(), T, d, scaled, below), every_row)
          << "component " << d << ", below " << below;
    }
  }
  EXPECT_GT(cut, 50);  // cuts through tall rows, so the top end read is not the rows' own
}

TEST(TallCellVelocity, LevelSetKernelsFromTheFirstRowEqualTheWholeLatticeAbove) {
  // the level set's advection and reinitialisation started at first_row write exactly what the
  // whole-lattice kernels write in the rows from first_row up, and nothing below it
  const MacGrid g{9, 16, 7, 0.1, {0, 0, 0}};
  const auto T = uneven_columns(g);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> R(-1.0, 1.0);
  std::vector<double> phi(g.padded_size()), vel[3];
  for (int k = -1; k <= g.nz; ++k)
    for (int j = -1; j <= g.ny; ++j)
      for (int i = -1; i <= g.nx; ++i) {
        const auto x = g.cell_centre(i, j, k);
        phi[g.index(i, j, k)] =
            x[1] - 0.9 + 0.2 * std::sin(4 * x[0]) * std::cos(3 * x[2]) + 0.02 * R(rng);
      }
  for (auto& v : vel) {
    v.resize(g.padded_size());
    for (auto& x : v) x = 0.5 * R(rng);
  }
  const auto P = kernels::to_view<Mem>(phi), U = kernels::to_view<Mem>(vel[0]),
             V = kernels::to_view<Mem>(vel[1]), W = kernels::to_view<Mem>(vel[2]);
  const double sentinel = 7.0;
  const auto run = [&](int first_row, bool advection) {
    const Kokkos::View<double*, Mem> out("out", g.padded_size());
    Kokkos::deep_copy(out, sentinel);
    const int none[3] = {0, 0, 0};
    if (advection)
      advect(Exec(), T, Staggering::centre, P, out, U, V, W, 0.05, P, 1.0, g, none, first_row);
    else
      reinitialise_step(Exec(), T, P, P, out, kernels::mac::box_edges(), first_row);
    return kernels::to_std_vector(out);
  };
  for (bool advection : {true, false}) {
    const auto whole = run(0, advection);
    for (int first_row : {4, 9}) {
      const auto part = run(first_row, advection);
      long changed = 0;
      for (int k = 0; k < g.nz; ++k)
        for (int j = 0; j < g.ny; ++j)
          for (int i = 0; i < g.nx; ++i) {
            const int c = g.index(i, j, k);
            if (j < first_row) {
              EXPECT_EQ(part[c], sentinel) << "row " << j << " below " << first_row;
            } else {
              EXPECT_EQ(part[c], whole[c]) << (advection ? "advection" : "reinitialisation")
                                           << " at (" << i << ", " << j << ", " << k << ")";
              changed += whole[c] != phi[c];
            }
          }
      EXPECT_GT(changed, 100);  // the kernels did change the rows they wrote
    }
  }
}

/// A smooth bump vanishing within two cells of the box.
double bump(const MacGrid& g, double x, double y, double z) {
  const double L[3] = {g.nx * g.h, g.ny * g.h, g.nz * g.h}, p[3] = {x, y, z};
  double b = 1.0;
  for (int d = 0; d < 3; ++d) {
    const double s = (p[d] - 2.5 * g.h) / (L[d] - 5 * g.h);
    b *= s > 0 && s < 1 ? std::sin(kernels::math::pi * s) * std::sin(kernels::math::pi * s) : 0.0;
  }
  return b;
}

TEST(TallCellVelocity, UpwindAdvectionInTallCellsConservesMomentum) {
  // every column one tall cell: all samples but the box faces use the upwind scheme, each
  // sample column as a whole
  const MacGrid g{12, 16, 10, 0.05, {0, 0, 0}};
  const auto T = columns(g, std::vector<int>(g.nx * g.nz, 0), std::vector<int>(g.nx * g.nz, g.ny));
  std::vector<double> f[3];
  for (int d = 0; d < 3; ++d) {
    f[d].assign(g.padded_size(), 0.0);
    for (int k = 0; k < g.nz + (d == 2); ++k)
      for (int j = 0; j < g.ny + (d == 1); ++j)
        for (int i = 0; i < g.nx + (d == 0); ++i) {
          double p[3];
          sample_position(g, static_cast<Staggering>(d), i, j, k, p);
          const double a[3] = {0.8, -0.5, 0.3};
          f[d][g.index(i, j, k)] =
              a[d] * bump(g, p[0], p[1], p[2]) * (1.0 + 0.5 * std::sin(7 * p[(d + 1) % 3]));
        }
  }
  const auto u = kernels::to_view<Mem>(f[0]), v = kernels::to_view<Mem>(f[1]),
             w = kernels::to_view<Mem>(f[2]);
  // linear in height in the tall cells, as the water step keeps the velocity there
  fit_linear_in_tall_cells(Exec(), T, 0, u);
  fit_linear_in_tall_cells(Exec(), T, 1, v);
  fit_linear_in_tall_cells(Exec(), T, 2, w);
  f[0] = kernels::to_std_vector(u), f[1] = kernels::to_std_vector(v),
  f[2] = kernels::to_std_vector(w);
  const Kokkos::View<double*, Mem> all_fluid("phi", g.padded_size());
  Kokkos::deep_copy(all_fluid, -1.0);
  const double dt = 0.4 * g.h / 0.8;  // Courant sum below one
  const Kokkos::View<double*, Mem> out("out", g.padded_size());
  double moved = 0.0;
  // u and w: their tall ranges end at the box's top and bottom, where v (the bump) is zero, so
  // no momentum leaves them. v's range ends at the faces just inside the box's, which the upwind
  // step does not update (in the water step a solid face below, the band's semi-Lagrangian
  // samples above) and through which momentum leaves a linear v; its fluxes inside the range
  // are those of the row-by-row step (AdvectionPerTallCellEqualsEveryRowThenTheFit).
  for (int d : {0, 2}) {
    advect(Exec(), T, static_cast<Staggering>(d), d == 0 ? u : w, out, u, v, w, dt, all_fluid, 1.0);
    const auto r = kernels::to_std_vector(out);
    double before = 0, after = 0, scale = 0;
    for (std::size_t c = 0; c < r.size(); ++c) {
      before += f[d][c], after += r[c], scale += std::abs(f[d][c]);
      moved = std::max(moved, std::abs(r[c] - f[d][c]));
    }
    EXPECT_NEAR(after, before, 1e-14 * scale) << "momentum of component " << d;
  }
  EXPECT_GT(moved, 1e-3);  // the field did move
}

TEST(TallCellVelocity, AdvectionPerTallCellEqualsEveryRowThenTheFit) {
  // Fields linear in height in uneven tall cells (as the water step keeps them), random
  // elsewhere: advect() updates a tall range as a whole from closed-form flux sums; that must
  // equal the upwind step of every row followed by the momentum-keeping fit, to round-off.
  const MacGrid g{9, 16, 7, 0.1, {0, 0, 0}};
  const auto T = uneven_columns(g);
  const auto th = uneven_columns<kernels::HostMemSpace>(g);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> R(-1.0, 1.0);
  std::vector<double> f[3];
  Kokkos::View<double*, Mem> vel[3];
  for (int d = 0; d < 3; ++d) {
    f[d].resize(g.padded_size());
    for (auto& x : f[d]) x = R(rng);
    vel[d] = kernels::to_view<Mem>(f[d]);
    fit_linear_in_tall_cells(Exec(), T, d, vel[d]);  // linear in the tall cells
    f[d] = kernels::to_std_vector(vel[d]);
  }
  const auto hu = kernels::to_view<kernels::HostMemSpace>(f[0]),
             hv = kernels::to_view<kernels::HostMemSpace>(f[1]),
             hw = kernels::to_view<kernels::HostMemSpace>(f[2]);
  const Kokkos::View<double*, Mem> all_fluid("phi", g.padded_size()), out("out", g.padded_size());
  Kokkos::deep_copy(all_fluid, -1.0);
  const double dt = 0.05;
  long whole = 0, sign_changes = 0;
  for (int d = 0; d < 3; ++d) {
    advect(Exec(), T, static_cast<Staggering>(d), vel[d], out, vel[0], vel[1], vel[2], dt,
           all_fluid, 1.0);
    const auto got = kernels::to_std_vector(out);
    // the reference: every tall row by conservative_upwind_sample, then the fit
    const auto hq = d == 0 ? hu : d == 1 ? hv : hw;
    Kokkos::View<double*, kernels::HostMemSpace> ref("ref", g.padded_size());
    Kokkos::deep_copy(ref, hq);
    for (int k = 0; k < g.nz + (d == 2); ++k)
      for (int i = 0; i < g.nx + (d == 0); ++i) {
        int lo, hi;
        th.tall_rows(d, i, k, lo, hi);
        for (int j = lo; j < hi; ++j)
          ref(g.index(i, j, k)) =
              conservative_upwind_sample(g, d, g.index(i, j, k), hq, hu, hv, hw, dt);
        if (hi - lo >= min_tall_sample_rows) ++whole;
        for (int j = lo + 1; j < hi; ++j)  // the column's own flux changes sign in the range
          sign_changes += (hq(g.index(i, j, k)) > 0) != (hq(g.index(i, j - 1, k)) > 0);
      }
    fit_linear_in_tall_cells(Kokkos::DefaultHostExecutionSpace(), th, d, ref);
    for (int k = 0; k < g.nz + (d == 2); ++k)
      for (int i = 0; i < g.nx + (d == 0); ++i) {
        int lo, hi;
        th.tall_rows(d, i, k, lo, hi);
        for (int j = lo; j < hi; ++j)
          EXPECT_NEAR(got[g.index(i, j, k)], ref(g.index(i, j, k)), 1e-13)
              << "component " << d << " sample column (" << i << ", " << k << ") row " << j;
      }
  }
  EXPECT_GT(whole, 100);        // many tall ranges updated as a whole
  EXPECT_GT(sign_changes, 20);  // and flows that change direction inside them
}

TEST(TallCellVelocity, UpwindAdvectionTranslatesLinearFieldsExactly) {
  // a constant velocity carries q = a + b.x exactly: dq = -dt (U . b)
  const MacGrid g{10, 12, 8, 0.1, {0, 0, 0}};
  const auto T = columns(g, std::vector<int>(g.nx * g.nz, 0), std::vector<int>(g.nx * g.nz, g.ny));
  const double U[3] = {0.3, -0.2, 0.25}, b[3] = {1.5, -0.7, 0.4};
  std::vector<double> vel[3], q(g.padded_size(), 0.0);
  for (int d = 0; d < 3; ++d) vel[d].assign(g.padded_size(), U[d]);
  for (int k = -1; k <= g.nz; ++k)
    for (int j = -1; j <= g.ny; ++j)
      for (int i = -1; i <= g.nx; ++i) {
        double p[3];
        sample_position(g, Staggering::x, i, j, k, p);
        q[g.index(i, j, k)] = 0.2 + b[0] * p[0] + b[1] * p[1] + b[2] * p[2];
      }
  const Kokkos::View<double*, Mem> all_fluid("phi", g.padded_size()), out("out", g.padded_size());
  Kokkos::deep_copy(all_fluid, -1.0);
  const double dt = 0.1;
  advect(Exec(), T, Staggering::x, kernels::to_view<Mem>(q), out, kernels::to_view<Mem>(vel[0]),
         kernels::to_view<Mem>(vel[1]), kernels::to_view<Mem>(vel[2]), dt, all_fluid, 1.0);
  const auto r = kernels::to_std_vector(out);
  const double change = -dt * (U[0] * b[0] + U[1] * b[1] + U[2] * b[2]);
  int checked = 0;
  for (int k = 1; k < g.nz - 1; ++k)
    for (int j = 1; j < g.ny - 1; ++j)
      for (int i = 1; i < g.nx; ++i, ++checked) {
        const int c = g.index(i, j, k);
        EXPECT_NEAR(r[c], q[c] + change, 1e-13);
      }
  EXPECT_GT(checked, 400);
}

}  // namespace
}  // namespace amphora::kernels::mac
