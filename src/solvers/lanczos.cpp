#include "solvers/lanczos.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <stdexcept>

namespace amphora::solvers {

std::pair<double, double> lanczos_extreme_eigenvalues(const std::vector<double>& alphas,
                                                      const std::vector<double>& betas) {
  const int n = static_cast<int>(alphas.size());
  if (n < 1 || static_cast<int>(betas.size()) < n - 1)
    throw std::invalid_argument("lanczos_extreme_eigenvalues: need n alphas and n-1 betas");
  Eigen::VectorXd diag(n), off(n > 1 ? n - 1 : 1);
  for (int i = 0; i < n; ++i) {
    diag[i] = 1.0 / alphas[i] + (i > 0 ? betas[i - 1] / alphas[i - 1] : 0.0);
    if (i + 1 < n) off[i] = std::sqrt(betas[i]) / alphas[i];
  }
  if (n == 1) return {diag[0], diag[0]};
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es;
  es.computeFromTridiagonal(diag, off.head(n - 1), Eigen::EigenvaluesOnly);
  return {es.eigenvalues()[0], es.eigenvalues()[n - 1]};
}

}  // namespace amphora::solvers
