#pragma once
// Extreme eigenvalues of the symmetric tridiagonal Lanczos matrix that CG builds for free
// from its step lengths alpha_i and direction updates beta_i (Saad, Iterative Methods, 6.7.3):
//   T_ii = 1/alpha_i + beta_{i-1}/alpha_{i-1},  T_i,i+1 = sqrt(beta_i)/alpha_i.
#include <utility>
#include <vector>

namespace amphora::solvers {

/// (smallest, largest) eigenvalue of the Lanczos matrix; alphas.size() >= 1,
/// betas.size() >= alphas.size() - 1.
std::pair<double, double> lanczos_extreme_eigenvalues(const std::vector<double>& alphas,
                                                      const std::vector<double>& betas);

}  // namespace amphora::solvers
