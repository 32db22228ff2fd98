#include "physics/channel_flow/channel_stokes.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <cmath>
#include <stdexcept>

namespace amphora::channel {

namespace {

using Matrix = Eigen::SparseMatrix<double>;

int wrap(int i, int n) { return ((i % n) + n) % n; }

/// Triplets of the 5-point Laplacian on an nx x rows block with homogeneous wall conditions:
/// `reflect` (u: ghost = -interior, the wall between ghost and interior) or not (v: the wall
/// row itself is known and outside the block).
void laplacian(std::vector<Eigen::Triplet<double>>& t, int nx, int rows, double hx, double hy,
               bool reflect, double scale, double diagonal) {
  const double cx = scale / (hx * hx), cy = scale / (hy * hy);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      double c = diagonal - 2 * cx - 2 * cy;
      t.emplace_back(r, j * nx + wrap(i - 1, nx), cx);
      t.emplace_back(r, j * nx + wrap(i + 1, nx), cx);
      if (j > 0) t.emplace_back(r, r - nx, cy);
      else if (reflect) c -= cy;
      if (j < rows - 1) t.emplace_back(r, r + nx, cy);
      else if (reflect) c -= cy;
      t.emplace_back(r, r, c);
    }
}

}  // namespace

struct ChannelStokes::Factors {
  Matrix lap_u, lap_v;  // homogeneous-wall Laplacians (for the explicit half)
  Eigen::SparseLU<Matrix> mu_, mv, mp;
};

ChannelStokes::ChannelStokes(const ChannelGrid& g, double rho, double mu, double dt)
    : g_(g), rho_(rho), mu_(mu), dt_(dt) {
  if (!(rho > 0) || !(mu > 0) || !(dt > 0))
    throw std::invalid_argument("channel Stokes: rho, mu and dt must be > 0");
  if (g.nx < 3 || g.ny < 2) throw std::invalid_argument("channel Stokes: grid needs nx >= 3, ny >= 2");
  const int nx = g.nx, ny = g.ny;
  f_ = std::make_unique<Factors>();
  auto build = [](int n, const std::vector<Eigen::Triplet<double>>& t) {
    Matrix m(n, n);
    m.setFromTriplets(t.begin(), t.end());
    return m;
  };
  std::vector<Eigen::Triplet<double>> t;
  laplacian(t, nx, ny, g.hx(), g.hy(), true, 1.0, 0.0);
  f_->lap_u = build(nx * ny, t);
  t.clear();
  laplacian(t, nx, ny - 1, g.hx(), g.hy(), false, 1.0, 0.0);
  f_->lap_v = build(nx * (ny - 1), t);
  // Crank–Nicolson: rho/dt I - mu/2 L.
  t.clear();
  laplacian(t, nx, ny, g.hx(), g.hy(), true, -0.5 * mu, rho / dt);
  f_->mu_.compute(build(nx * ny, t));
  t.clear();
  laplacian(t, nx, ny - 1, g.hx(), g.hy(), false, -0.5 * mu, rho / dt);
  f_->mv.compute(build(nx * (ny - 1), t));
  // The projection's Neumann Laplacian D G (no flux through the walls), one cell pinned.
  t.clear();
  const double cx = 1 / (g.hx() * g.hx()), cy = 1 / (g.hy() * g.hy());
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      if (r == 0) {
        t.emplace_back(0, 0, 1.0);
        continue;
      }
      double c = -2 * cx;
      t.emplace_back(r, j * nx + wrap(i - 1, nx), cx);
      t.emplace_back(r, j * nx + wrap(i + 1, nx), cx);
      if (j > 0) {
        t.emplace_back(r, r - nx, cy);
        c -= cy;
      }
      if (j < ny - 1) {
        t.emplace_back(r, r + nx, cy);
        c -= cy;
      }
      t.emplace_back(r, r, c);
    }
  f_->mp.compute(build(nx * ny, t));
  if (f_->mu_.info() != Eigen::Success || f_->mv.info() != Eigen::Success ||
      f_->mp.info() != Eigen::Success)
    throw std::runtime_error("channel Stokes: factorisation failed");
  u_.assign(size_t(nx) * ny, 0.0);
  v_.assign(size_t(nx) * (ny + 1), 0.0);
  p_.assign(size_t(nx) * ny, 0.0);
}

ChannelStokes::~ChannelStokes() = default;
ChannelStokes::ChannelStokes(ChannelStokes&&) noexcept = default;

void ChannelStokes::set_state(double t, std::vector<double> u, std::vector<double> v,
                              std::vector<double> p) {
  const size_t nx = g_.nx, ny = g_.ny;
  if (u.size() != nx * ny || v.size() != nx * (ny + 1) || p.size() != nx * ny)
    throw std::invalid_argument("channel Stokes: state arrays have the wrong size");
  t_ = t;
  u_ = std::move(u);
  v_ = std::move(v);
  p_ = std::move(p);
}

void ChannelStokes::step(const StokesData& d) {
  const int nx = g_.nx, ny = g_.ny;
  const double hx = g_.hx(), hy = g_.hy(), t0 = t_, t1 = t_ + dt_, th = t_ + 0.5 * dt_;
  using Vec = Eigen::VectorXd;
  // u: explicit half of Crank–Nicolson, wall data of both levels, old pressure gradient, force.
  Vec un = Eigen::Map<const Vec>(u_.data(), nx * ny);
  Vec ru = (rho_ / dt_) * un + 0.5 * mu_ * (f_->lap_u * un);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      const double x = u_x(i), y = u_y(j);
      if (j == 0) ru[r] += mu_ * (d.u_bottom(x, t0) + d.u_bottom(x, t1)) / (hy * hy);
      if (j == ny - 1) ru[r] += mu_ * (d.u_top(x, t0) + d.u_top(x, t1)) / (hy * hy);
      ru[r] += -(p_[r] - p_[j * nx + wrap(i - 1, nx)]) / hx + d.fx(x, y, th);
    }
  const Vec us = f_->mu_.solve(ru);
  // v on the interior faces (rows 1..ny-1); the wall rows are data.
  Vec vn(nx * (ny - 1));
  for (int j = 1; j < ny; ++j)
    for (int i = 0; i < nx; ++i) vn[(j - 1) * nx + i] = v_[size_t(j) * nx + i];
  Vec rv = (rho_ / dt_) * vn + 0.5 * mu_ * (f_->lap_v * vn);
  for (int j = 1; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = (j - 1) * nx + i;
      const double x = v_x(i), y = v_y(j);
      if (j == 1) rv[r] += 0.5 * mu_ * (d.v_bottom(x, t0) + d.v_bottom(x, t1)) / (hy * hy);
      if (j == ny - 1) rv[r] += 0.5 * mu_ * (d.v_top(x, t0) + d.v_top(x, t1)) / (hy * hy);
      rv[r] += -(p_[j * nx + i] - p_[(j - 1) * nx + i]) / hy + d.fy(x, y, th);
    }
  const Vec vs_in = f_->mv.solve(rv);
  std::vector<double> vs(size_t(nx) * (ny + 1));
  for (int i = 0; i < nx; ++i) {
    vs[i] = d.v_bottom(v_x(i), t1);
    vs[size_t(ny) * nx + i] = d.v_top(v_x(i), t1);
  }
  for (int j = 1; j < ny; ++j)
    for (int i = 0; i < nx; ++i) vs[size_t(j) * nx + i] = vs_in[(j - 1) * nx + i];
  // Projection: lap phi = rho/dt div v*, no flux through the walls (v* carries the wall data).
  Vec div(nx * ny), rhs(nx * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      div[r] = (us[j * nx + wrap(i + 1, nx)] - us[r]) / hx +
               (vs[size_t(j + 1) * nx + i] - vs[size_t(j) * nx + i]) / hy;
      rhs[r] = rho_ / dt_ * div[r];
    }
  rhs[0] = 0.0;
  Vec phi = f_->mp.solve(rhs);
  phi.array() -= phi.mean();
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      u_[r] = us[r] - dt_ / rho_ * (phi[r] - phi[j * nx + wrap(i - 1, nx)]) / hx;
      p_[r] += phi[r] - 0.5 * mu_ * div[r];
    }
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const size_t r = size_t(j) * nx + i;
      v_[r] = (j == 0 || j == ny) ? vs[r]
                                  : vs[r] - dt_ / rho_ * (phi[j * nx + i] - phi[(j - 1) * nx + i]) / hy;
    }
  t_ = t1;
}

double ChannelStokes::max_divergence() const {
  const int nx = g_.nx, ny = g_.ny;
  double m = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      m = std::max(m, std::abs((u_[j * nx + wrap(i + 1, nx)] - u_[j * nx + i]) / g_.hx() +
                               (v_[size_t(j + 1) * nx + i] - v_[size_t(j) * nx + i]) / g_.hy()));
  return m;
}

}  // namespace amphora::channel
