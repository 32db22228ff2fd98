#include "physics/channel_flow/channel_pressure.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <stdexcept>
#include <array>

namespace amphora::physics::channel_flow {

struct ChannelPressure::Factor {
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
};

ChannelPressure::ChannelPressure(const ChannelGrid& g, double alpha,
                                 const std::array<double, 5>& top_operator)
    : g_(g), alpha_(alpha) {
  bool any = false;
  for (double b : top_operator) any = any || b != 0.0;
  if (alpha < 0 || !any)
    throw std::invalid_argument("channel pressure: need alpha >= 0 and a non-zero top operator");
  if (g.nx < 3 || g.ny < 2 || !(g.length > 0) || !(g.depth > 0))
    throw std::invalid_argument("channel pressure: grid needs nx >= 3, ny >= 2 and positive size");
  const int nx = g.nx, ny = g.ny;
  const double cx = 1.0 / (g.hx() * g.hx()), cy = 1.0 / (g.hy() * g.hy());
  auto id = [nx](int i, int j) { return j * nx + ((i % nx) + nx) % nx; };
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j <= ny; ++j) {  // the Laplacian at every node
    for (int i = 0; i < nx; ++i) {
      const int r = id(i, j);
      if (alpha == 0 && r == 0) {  // pin one value; solve() shifts the constant afterwards
        t.emplace_back(r, r, 1.0);
        continue;
      }
      t.emplace_back(r, id(i - 1, j), cx);
      t.emplace_back(r, id(i + 1, j), cx);
      t.emplace_back(r, r, -2 * (cx + cy));
      t.emplace_back(r, id(i, j + 1), j == 0 ? 0.0 : cy);  // row ny + 1 is the ghost line
      t.emplace_back(r, id(i, j == 0 ? 1 : j - 1), j == 0 ? 2 * cy : cy);  // bottom: ghost = p_1
    }
  }
  for (int i = 0; i < nx; ++i) {  // the top condition, one row per ghost
    const int r = id(i, ny + 1);
    t.emplace_back(r, id(i, ny), alpha);
    for (int o = -2; o <= 2; ++o) {
      const double b = top_operator[o + 2] / (2 * g.hy());
      t.emplace_back(r, id(i + o, ny + 1), b);
      t.emplace_back(r, id(i + o, ny - 1), -b);
    }
  }
  const int n = nx * (ny + 2);
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  factor_ = std::make_unique<Factor>();
  factor_->lu.compute(a);
  if (factor_->lu.info() != Eigen::Success)
    throw std::runtime_error("channel pressure: factorisation failed");
}

ChannelPressure::~ChannelPressure() = default;
ChannelPressure::ChannelPressure(ChannelPressure&&) noexcept = default;

std::vector<double> ChannelPressure::solve(const std::vector<double>& g, double mean_top) const {
  const int nx = g_.nx, ny = g_.ny;
  if (int(g.size()) != nx) throw std::invalid_argument("channel pressure: g needs nx values");
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nx * (ny + 2));
  for (int i = 0; i < nx; ++i) rhs[(ny + 1) * nx + i] = g[i];
  const Eigen::VectorXd p = factor_->lu.solve(rhs);
  std::vector<double> out(p.data(), p.data() + p.size());
  if (alpha_ == 0) {
    double mean = 0;
    for (int i = 0; i < nx; ++i) mean += out[ny * nx + i];
    const double shift = mean_top - mean / nx;
    for (double& v : out) v += shift;
  }
  return out;
}

std::vector<double> ChannelPressure::top_normal_derivative(const std::vector<double>& p) const {
  const int nx = g_.nx, ny = g_.ny;
  std::vector<double> out(nx);
  for (int i = 0; i < nx; ++i)
    out[i] = (p[size_t(ny + 1) * nx + i] - p[size_t(ny - 1) * nx + i]) / (2 * g_.hy());
  return out;
}

}  // namespace amphora::physics::channel_flow
