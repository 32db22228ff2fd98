#include "physics/beam/euler_bernoulli_beam.hpp"

#include <Eigen/Sparse>
#include <array>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <stdexcept>
#include <string>

namespace amphora::physics::beam {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("beam: " + what);
}

/// The periodic 5-point stencil of A: A eta_i = sum_{o=-2..2} c[o+2] eta_{i+o}.
std::array<double, 5> beam_stencil(const BeamParameters& p, double h) {
  const double t = p.tension / (h * h), b = p.stiffness / (h * h * h * h);
  return {b, -t - 4 * b, p.spring + 2 * t + 6 * b, -t - 4 * b, b};
}

}  // namespace

double beam_frequency(const BeamParameters& p, double k) {
  return std::sqrt((p.spring + p.tension * k * k + p.stiffness * k * k * k * k) / p.rho_h);
}

struct EulerBernoulliBeam::Factor {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
};

EulerBernoulliBeam::EulerBernoulliBeam(const BeamParameters& p, double dt)
    : p_(p), dt_(dt), h_(p.length / p.points) {
  require(p.rho_h > 0, "rho_h must be > 0");
  require(p.spring >= 0, "spring (K) must be >= 0");
  require(p.tension >= 0, "tension (T) must be >= 0");
  require(p.stiffness >= 0, "stiffness (B) must be >= 0");
  require(p.length > 0, "length must be > 0");
  require(p.points >= 5, "points must be >= 5 (the stencil is 5 wide)");
  require(dt > 0, "dt must be > 0");
  const int n = p.points;
  eta_.assign(n, 0.0);
  v_.assign(n, 0.0);
  a_.assign(n, 0.0);
  const auto c = beam_stencil(p, h_);
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i)
    for (int o = -2; o <= 2; ++o) {
      const double value = 0.25 * dt * dt * c[o + 2] + (o == 0 ? p.rho_h : 0.0);
      entries.emplace_back(i, ((i + o) % n + n) % n, value);
    }
  Eigen::SparseMatrix<double> s(n, n);
  s.setFromTriplets(entries.begin(), entries.end());
  factor_ = std::make_unique<Factor>();
  factor_->ldlt.compute(s);
  if (factor_->ldlt.info() != Eigen::Success)
    throw std::runtime_error("beam: factorisation failed");
}

EulerBernoulliBeam::~EulerBernoulliBeam() = default;
EulerBernoulliBeam::EulerBernoulliBeam(EulerBernoulliBeam&&) noexcept = default;

std::vector<double> EulerBernoulliBeam::restoring_force(const std::vector<double>& eta) const {
  const int n = p_.points;
  const auto c = beam_stencil(p_, h_);
  std::vector<double> out(n);
  for (int i = 0; i < n; ++i) {
    double s = 0;
    for (int o = -2; o <= 2; ++o) s += c[o + 2] * eta[((i + o) % n + n) % n];
    out[i] = s;
  }
  return out;
}

void EulerBernoulliBeam::set_state(double t, const std::vector<double>& eta,
                                   const std::vector<double>& v, const std::vector<double>& f) {
  restore_state(t, eta, v, f);  // checks the sizes; the acceleration follows from the load
  const auto r = restoring_force(eta_);
  for (size_t i = 0; i < a_.size(); ++i) a_[i] = (f[i] - r[i]) / p_.rho_h;
}

void EulerBernoulliBeam::restore_state(double t, const std::vector<double>& eta,
                                       const std::vector<double>& v, const std::vector<double>& a) {
  const size_t n = p_.points;
  require(eta.size() == n && v.size() == n && a.size() == n,
          "state arrays must have `points` entries");
  t_ = t;
  eta_ = eta;
  v_ = v;
  a_ = a;
}

std::vector<double> EulerBernoulliBeam::predictor() const {
  std::vector<double> pred(p_.points);
  for (int i = 0; i < p_.points; ++i) pred[i] = eta_[i] + dt_ * v_[i] + 0.25 * dt_ * dt_ * a_[i];
  return pred;
}

std::vector<double> EulerBernoulliBeam::acceleration_after(
    const std::vector<double>& f_next) const {
  const int n = p_.points;
  require(int(f_next.size()) == n, "load must have `points` entries");
  // (rho_h + dt^2/4 A) a_new = f - A eta*, eta* the predictor.
  const auto r = restoring_force(predictor());
  Eigen::VectorXd rhs(n);
  for (int i = 0; i < n; ++i) rhs[i] = f_next[i] - r[i];
  const Eigen::VectorXd a_new = factor_->ldlt.solve(rhs);
  return std::vector<double>(a_new.data(), a_new.data() + n);
}

void EulerBernoulliBeam::step(const std::vector<double>& f_next) {
  advance_with(acceleration_after(f_next));
}

void EulerBernoulliBeam::advance_with(const std::vector<double>& a_new) {
  const int n = p_.points;
  const auto pred = predictor();
  for (int i = 0; i < n; ++i) {
    eta_[i] = pred[i] + 0.25 * dt_ * dt_ * a_new[i];
    v_[i] += 0.5 * dt_ * (a_[i] + a_new[i]);
    a_[i] = a_new[i];
  }
  t_ += dt_;
}

std::array<double, 5> EulerBernoulliBeam::stencil() const { return beam_stencil(p_, h_); }

double EulerBernoulliBeam::energy() const {
  const auto r = restoring_force(eta_);
  double e = 0;
  for (int i = 0; i < p_.points; ++i) e += p_.rho_h * v_[i] * v_[i] + eta_[i] * r[i];
  return 0.5 * h_ * e;
}

}  // namespace amphora::physics::beam
