#include "physics/channel_flow/channel_stokes.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace amphora::physics::channel_flow {

namespace {

using Matrix = Eigen::SparseMatrix<double>;

int wrap(int i, int n) { return ((i % n) + n) % n; }

/// Triplets of the 5-point Laplacian on an nx x rows block whose ghost rows below and above
/// are `bottom` and `top` times the row next to them (u at a velocity wall: -1, the wall half
/// way between ghost and interior; v: 0, the wall row itself is known and outside the block;
/// an impedance top: its Robin coefficient).
void laplacian(std::vector<Eigen::Triplet<double>>& t, int nx, int rows, double hx, double hy,
               double bottom, double top, double scale, double diagonal) {
  const double cx = scale / (hx * hx), cy = scale / (hy * hy);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      double c = diagonal - 2 * cx - 2 * cy;
      t.emplace_back(r, j * nx + wrap(i - 1, nx), cx);
      t.emplace_back(r, j * nx + wrap(i + 1, nx), cx);
      if (j > 0)
        t.emplace_back(r, r - nx, cy);
      else
        c += bottom * cy;
      if (j < rows - 1)
        t.emplace_back(r, r + nx, cy);
      else
        c += top * cy;
      t.emplace_back(r, r, c);
    }
}

}  // namespace

struct ChannelStokes::Factors {
  Matrix lap_u, lap_v;  // homogeneous-wall Laplacians (for the explicit half)
  Eigen::SparseLU<Matrix> mu_, mv, mp;
};

ChannelStokes::ChannelStokes(const ChannelGrid& g, double rho, double mu, double dt,
                             std::optional<TopImpedance> top)
    : g_(g), rho_(rho), mu_(mu), dt_(dt), top_(top) {
  if (!(rho > 0) || !(mu > 0) || !(dt > 0))
    throw std::invalid_argument("channel Stokes: rho, mu and dt must be > 0");
  if (top && !(top->z_normal >= 0 && top->z_shear >= 0))
    throw std::invalid_argument("channel Stokes: the top impedances must be >= 0");
  if (g.nx < 3 || g.ny < 2)
    throw std::invalid_argument("channel Stokes: grid needs nx >= 3, ny >= 2");
  const int nx = g.nx, ny = g.ny;
  const double hx = g.hx(), hy = g.hy();
  f_ = std::make_unique<Factors>();
  auto build = [](int n, const std::vector<Eigen::Triplet<double>>& t) {
    Matrix m(n, n);
    m.setFromTriplets(t.begin(), t.end());
    return m;
  };
  std::vector<Eigen::Triplet<double>> t;
  laplacian(t, nx, ny, hx, hy, -1, -1, 1.0, 0.0);
  f_->lap_u = build(nx * ny, t);
  t.clear();
  laplacian(t, nx, ny - 1, hx, hy, 0, 0, 1.0, 0.0);
  f_->lap_v = build(nx * (ny - 1), t);
  // Crank–Nicolson: rho/dt I - mu/2 L, u and v apart; an impedance top's u ghost is
  // cu u + data, cu = (mu/hy - z_s/2) / (mu/hy + z_s/2) (header).
  const double cu = top ? (mu / hy - 0.5 * top->z_shear) / (mu / hy + 0.5 * top->z_shear) : -1.0;
  t.clear();
  laplacian(t, nx, ny, hx, hy, -1, cu, -0.5 * mu, rho / dt);
  f_->mu_.compute(build(nx * ny, t));
  t.clear();
  laplacian(t, nx, ny - 1, hx, hy, 0, 0, -0.5 * mu, rho / dt);
  f_->mv.compute(build(nx * (ny - 1), t));
  if (f_->mu_.info() != Eigen::Success || f_->mv.info() != Eigen::Success)
    throw std::runtime_error("channel Stokes: factorisation failed");
  // The projection's Laplacian D G: no flux through a velocity wall (one cell pinned if both
  // are), the Robin ghost at an impedance top.
  t.clear();
  laplacian(t, nx, ny, hx, hy, 1, top ? phi_ghost(hy) : 1, 1.0, 0.0);
  if (!top) {
    t.erase(std::remove_if(t.begin(), t.end(), [](const auto& e) { return e.row() == 0; }),
            t.end());
    t.emplace_back(0, 0, 1.0);
  } else {
    // The ghost's implicit viscous part eta L_x phi (header), in the top row's flux cy (a - b).
    const double cy = 1 / (hy * hy), eta = phi_viscous(hy) / (hx * hx);
    for (int i = 0; i < nx; ++i) {
      const int r = (ny - 1) * nx + i;
      for (auto [row, w] : {std::pair{ny - 1, 1.5}, std::pair{ny - 2, -0.5}}) {
        const int c = row * nx;
        t.emplace_back(r, c + wrap(i - 1, nx), cy * eta * w);
        t.emplace_back(r, c + i, -2 * cy * eta * w);
        t.emplace_back(r, c + wrap(i + 1, nx), cy * eta * w);
      }
    }
  }
  f_->mp.compute(build(nx * ny, t));
  if (f_->mp.info() != Eigen::Success)
    throw std::runtime_error("channel Stokes: factorisation failed");
  u_.assign(size_t(nx) * ny, 0.0);
  v_.assign(size_t(nx) * (ny + 1), 0.0);
  p_.assign(size_t(nx) * ny, 0.0);
  if (top) top_state_.assign(size_t(nx), 0.0);
}

ChannelStokes::~ChannelStokes() = default;
ChannelStokes::ChannelStokes(ChannelStokes&&) noexcept = default;

double ChannelStokes::phi_ghost(double hy) const {
  // -(3/4)(a + b) - beta (a - b) = data, beta = z_p dt / (rho hy): a = phi_ghost b + data'.
  const double beta = top_->z_normal * dt_ / (rho_ * hy);
  return (beta - 0.75) / (beta + 0.75);
}

double ChannelStokes::phi_viscous(double hy) const {
  // a = phi_ghost b + phi_viscous L_x phi + data: the 2 mu dt / rho of -2 mu u_x^{n+1}.
  const double beta = top_->z_normal * dt_ / (rho_ * hy);
  return 2 * mu_ * dt_ / rho_ / (beta + 0.75);
}

std::vector<double> ChannelStokes::viscous_part(const Eigen::VectorXd& phi) const {
  // L_x phi on the wall: the second x difference of the two rows below, extrapolated.
  const int nx = g_.nx, ny = g_.ny;
  const double hx = g_.hx();
  std::vector<double> l(nx);
  for (int i = 0; i < nx; ++i) {
    auto dxx = [&](int row) {
      const size_t c = size_t(row) * nx;
      return (phi[c + wrap(i - 1, nx)] - 2 * phi[c + i] + phi[c + wrap(i + 1, nx)]) / (hx * hx);
    };
    l[i] = 1.5 * dxx(ny - 1) - 0.5 * dxx(ny - 2);
  }
  return l;
}

void ChannelStokes::set_state(double t, std::vector<double> u, std::vector<double> v,
                              std::vector<double> p, std::vector<double> top_state) {
  const size_t nx = g_.nx, ny = g_.ny;
  if (u.size() != nx * ny || v.size() != nx * (ny + 1) || p.size() != nx * ny ||
      top_state.size() != (top_ ? nx : 0))
    throw std::invalid_argument("channel Stokes: state arrays have the wrong size");
  top_state_ = std::move(top_state);
  t_ = t;
  u_ = std::move(u);
  v_ = std::move(v);
  p_ = std::move(p);
}

void ChannelStokes::step(const StokesData& d) {
  const int nx = g_.nx, ny = g_.ny;
  const double hx = g_.hx(), hy = g_.hy(), t0 = t_, t1 = t_ + dt_, th = t_ + 0.5 * dt_;
  const size_t top_row = size_t(ny) * nx, last = size_t(ny - 1) * nx;
  using Vec = Eigen::VectorXd;
  // The top's normal velocity at t1: wall data, or (impedance top) a guess the projection corrects.
  std::vector<double> v_top1(nx), u_ghost_data(nx, 0.0);
  for (int i = 0; i < nx; ++i) v_top1[i] = d.v_top(v_x(i), t1);
  const double m = top_ ? mu_ / hy + 0.5 * top_->z_shear : 1.0;
  if (top_)  // the u Robin condition at t1: ghost = cu u + data
    for (int i = 0; i < nx; ++i)
      u_ghost_data[i] =
          (d.g_top_x(u_x(i), t1) - mu_ * (v_top1[i] - v_top1[wrap(i - 1, nx)]) / hx) / m;
  // u: explicit half of Crank–Nicolson, wall data of both levels, old pressure gradient, force.
  Vec un = Eigen::Map<const Vec>(u_.data(), nx * ny);
  Vec ru = (rho_ / dt_) * un + 0.5 * mu_ * (f_->lap_u * un);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      const double x = u_x(i), y = u_y(j);
      if (j == 0) ru[r] += mu_ * (d.u_bottom(x, t0) + d.u_bottom(x, t1)) / (hy * hy);
      if (j == ny - 1) {
        if (top_)  // the old ghost 2 u_wall - u (lap_u has -u), the new one's data
          ru[r] += 0.5 * mu_ * (2 * top_state_[i] + u_ghost_data[i]) / (hy * hy);
        else
          ru[r] += mu_ * (d.u_top(x, t0) + d.u_top(x, t1)) / (hy * hy);
      }
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
      if (j == ny - 1)
        rv[r] += 0.5 * mu_ * ((top_ ? v_[top_row + i] : d.v_top(x, t0)) + v_top1[i]) / (hy * hy);
      rv[r] += -(p_[j * nx + i] - p_[(j - 1) * nx + i]) / hy + d.fy(x, y, th);
    }
  const Vec vs_in = f_->mv.solve(rv);
  std::vector<double> vs(size_t(nx) * (ny + 1));
  for (int i = 0; i < nx; ++i) {
    vs[i] = d.v_bottom(v_x(i), t1);
    vs[top_row + i] = v_top1[i];
  }
  for (int j = 1; j < ny; ++j)
    for (int i = 0; i < nx; ++i) vs[size_t(j) * nx + i] = vs_in[(j - 1) * nx + i];
  // Projection: lap phi = rho/dt div v*, no flux through velocity walls (v* carries their data).
  Vec div(nx * ny), rhs(nx * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      div[r] = (us[j * nx + wrap(i + 1, nx)] - us[r]) / hx +
               (vs[size_t(j + 1) * nx + i] - vs[size_t(j) * nx + i]) / hy;
      rhs[r] = rho_ / dt_ * div[r];
    }
  std::vector<double> u_wall(nx), phi_ghost_data(nx, 0.0);
  if (top_) {
    // The Robin condition on phi at the interface (header): ghost = phi_ghost b + data.
    const double cu = (mu_ / hy - 0.5 * top_->z_shear) / m;
    for (int i = 0; i < nx; ++i) u_wall[i] = 0.5 * ((1 + cu) * us[last + i] + u_ghost_data[i]);
    const double beta = top_->z_normal * dt_ / (rho_ * hy);
    for (int i = 0; i < nx; ++i) {
      const double p_wall = 0.5 * (3 * p_[last + i] - p_[last - nx + i]);  // p^{n-1/2} at y = 0
      // -v_y on the wall: u_x of the two rows below, extrapolated (the wall's own u, through
      // the ghost, carries the guessed v_x: explicit feedback that the light solids amplify).
      auto u_x_row = [&](size_t row) { return (us[row + wrap(i + 1, nx)] - us[row + i]) / hx; };
      const double u_x = 1.5 * u_x_row(last) - 0.5 * u_x_row(last - nx);
      const double r = d.g_top_y(v_x(i), t1) + p_wall - 0.75 * mu_ * div[last + i] + 2 * mu_ * u_x -
                       top_->z_normal * v_top1[i];
      phi_ghost_data[i] = -r / (beta + 0.75);
      rhs[last + i] -= phi_ghost_data[i] / (hy * hy);
    }
  } else {
    rhs[0] = 0.0;
  }
  Vec phi = f_->mp.solve(rhs);
  if (!top_) phi.array() -= phi.mean();
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int r = j * nx + i;
      u_[r] = us[r] - dt_ / rho_ * (phi[r] - phi[j * nx + wrap(i - 1, nx)]) / hx;
      p_[r] += phi[r] - 0.5 * mu_ * div[r];
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const size_t r = size_t(j) * nx + i;
      v_[r] = j == 0 ? vs[r] : vs[r] - dt_ / rho_ * (phi[j * nx + i] - phi[(j - 1) * nx + i]) / hy;
    }
  if (top_) {  // the interface moves with the projection: v = v* - dt/rho phi_y, u likewise
    const double phi_c = phi_ghost(hy), phi_v = phi_viscous(hy);
    const std::vector<double> l = viscous_part(phi);
    std::vector<double> phi_wall(nx);
    for (int i = 0; i < nx; ++i) {
      const double ghost = phi_c * phi[last + i] + phi_v * l[i] + phi_ghost_data[i];
      v_[top_row + i] = vs[top_row + i] - dt_ / rho_ * (ghost - phi[last + i]) / hy;
      phi_wall[i] = 0.5 * (ghost + phi[last + i]);
    }
    for (int i = 0; i < nx; ++i)
      top_state_[i] = u_wall[i] - dt_ / rho_ * (phi_wall[i] - phi_wall[wrap(i - 1, nx)]) / hx;
  } else {
    for (int i = 0; i < nx; ++i) v_[top_row + i] = vs[top_row + i];
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

}  // namespace amphora::physics::channel_flow
