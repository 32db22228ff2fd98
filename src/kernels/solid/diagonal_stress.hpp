#pragma once
// Isotropic hyperelastic models as functions of the diagonalised deformation gradient F^ =
// diag(s): the diagonal first Piola-Kirchhoff stress P^(s) and its Jacobian dP^_i/ds_j.
// The invertible-FEM extrapolation (Irving, Teran & Fedkiw, SCA 2004, section 6) evaluates a
// model at s* = max(s, s_c) entrywise and extends it linearly, P^(s) = P^(s*) + dP^(s*) (s - s*):
// continuous across s_c, finite for inverted elements (s_2 < 0), and pushing them back.
#include "kernels/solid/mat3.hpp"

namespace amphora::kernels::solid {

enum class Hyperelastic { neo_hookean, corotated, st_venant_kirchhoff };

struct Material {
  Hyperelastic model = Hyperelastic::neo_hookean;
  double mu = 1.0, lambda = 1.0;  ///< Lame parameters [Pa]
  /// Singular values below this are extrapolated (Irving et al. 2004); <= 0: no extrapolation
  /// (the standard model, which breaks down under inversion).
  double s_clamp = 0.25;
};

struct DiagonalStress {
  Vec3 P;      ///< P^_i
  Mat3 dP_ds;  ///< dP^_i / ds_j (symmetric: P^ derives from an energy)
};

namespace diagonal_stress_detail {

/// Compressible neo-Hookean, psi = mu/2 (sum s^2 - 3) - mu log J + lambda/2 (log J)^2.
KOKKOS_INLINE_FUNCTION DiagonalStress neo_hookean(const Vec3& s, double mu, double lambda) {
  DiagonalStress r;
  const double log_j = math::log(s[0] * s[1] * s[2]);
  for (int i = 0; i < 3; ++i) {
    r.P[i] = mu * s[i] - (mu - lambda * log_j) / s[i];
    for (int j = 0; j < 3; ++j) r.dP_ds(i, j) = lambda / (s[i] * s[j]);
    r.dP_ds(i, i) += mu + (mu - lambda * log_j) / (s[i] * s[i]);
  }
  return r;
}

/// Corotated linear elasticity, psi = mu sum (s - 1)^2 + lambda/2 (sum (s - 1))^2.
KOKKOS_INLINE_FUNCTION DiagonalStress corotated(const Vec3& s, double mu, double lambda) {
  DiagonalStress r;
  const double tr = s[0] + s[1] + s[2] - 3.0;
  for (int i = 0; i < 3; ++i) {
    r.P[i] = 2.0 * mu * (s[i] - 1.0) + lambda * tr;
    for (int j = 0; j < 3; ++j) r.dP_ds(i, j) = lambda;
    r.dP_ds(i, i) += 2.0 * mu;
  }
  return r;
}

/// St Venant-Kirchhoff, psi = mu |E|^2 + lambda/2 (tr E)^2 with E^ = (s^2 - 1)/2.
KOKKOS_INLINE_FUNCTION DiagonalStress st_venant_kirchhoff(const Vec3& s, double mu, double lambda) {
  DiagonalStress r;
  const double tr = 0.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] - 3.0);
  for (int i = 0; i < 3; ++i) {
    r.P[i] = s[i] * (mu * (s[i] * s[i] - 1.0) + lambda * tr);
    for (int j = 0; j < 3; ++j) r.dP_ds(i, j) = lambda * s[i] * s[j];
    r.dP_ds(i, i) += mu * (3.0 * s[i] * s[i] - 1.0) + lambda * tr;
  }
  return r;
}

/// The strain energy density psi(s) of each model above.
KOKKOS_INLINE_FUNCTION double energy(const Material& m, const Vec3& s) {
  const double mu = m.mu, lambda = m.lambda;
  switch (m.model) {
    case Hyperelastic::corotated: {
      const double tr = s[0] + s[1] + s[2] - 3.0;
      double e = 0.5 * lambda * tr * tr;
      for (int i = 0; i < 3; ++i) e += mu * (s[i] - 1.0) * (s[i] - 1.0);
      return e;
    }
    case Hyperelastic::st_venant_kirchhoff: {
      double tr = 0.0, e = 0.0;
      for (int i = 0; i < 3; ++i) {
        const double Ei = 0.5 * (s[i] * s[i] - 1.0);
        tr += Ei, e += mu * Ei * Ei;
      }
      return e + 0.5 * lambda * tr * tr;
    }
    default: {
      const double log_j = math::log(s[0] * s[1] * s[2]);
      return 0.5 * mu * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] - 3.0) - mu * log_j +
             0.5 * lambda * log_j * log_j;
    }
  }
}

KOKKOS_INLINE_FUNCTION DiagonalStress evaluate(const Material& m, const Vec3& s) {
  switch (m.model) {
    case Hyperelastic::corotated: return corotated(s, m.mu, m.lambda);
    case Hyperelastic::st_venant_kirchhoff: return st_venant_kirchhoff(s, m.mu, m.lambda);
    default: return neo_hookean(s, m.mu, m.lambda);
  }
}

}  // namespace diagonal_stress_detail

/// P^(s) and dP^/ds, extrapolated linearly below m.s_clamp; there dP_ds is the Jacobian at the
/// clamped point (exact in the clamped entries, first order in the others). St Venant-Kirchhoff
/// softens under compression (P^ peaks near s = 1/sqrt(3)), so below that its extrapolation
/// is finite but does not push inverted elements back; neo-Hookean and corotated do.
KOKKOS_INLINE_FUNCTION DiagonalStress diagonal_stress(const Material& m, const Vec3& s) {
  Vec3 c = s;
  bool clamped = false;
  for (int i = 0; i < 3; ++i)
    if (m.s_clamp > 0.0 && s[i] < m.s_clamp) c[i] = m.s_clamp, clamped = true;
  DiagonalStress r = diagonal_stress_detail::evaluate(m, c);
  if (clamped)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.P[i] += r.dP_ds(i, j) * (s[j] - c[j]);
  return r;
}

/// Whether the closed forms below apply: not corotated (it needs the rotation), and every
/// singular value above s_clamp, which J > s_clamp |F|_F^2 guarantees (s_min >= J / s_max^2
/// >= J / |F|_F^2).
KOKKOS_INLINE_FUNCTION bool closed_form_applies(const Material& m, const Mat3& F, double J) {
  const double f = frobenius(F);
  return m.model != Hyperelastic::corotated && J > 0.0 && J > m.s_clamp * f * f;
}

/// P(F) without the SVD where that gives the same stress: neo-Hookean, P = mu (F - F^-T) +
/// lambda log J F^-T, and St Venant-Kirchhoff, P = F (2 mu E + lambda tr E I). Returns false
/// (P untouched) where closed_form_applies does not: there the SVD path is needed.
KOKKOS_INLINE_FUNCTION bool closed_form_stress(const Material& m, const Mat3& F, double J,
                                               Mat3& P) {
  if (!closed_form_applies(m, F, J)) return false;
  if (m.model == Hyperelastic::neo_hookean) {
    const Mat3 Finv_t = transpose(inverse(F));
    const double c = m.lambda * math::log(J) - m.mu;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) P(i, j) = m.mu * F(i, j) + c * Finv_t(i, j);
    return true;
  }
  Mat3 S = transpose(F) * F;  // C, then 2 mu E + lambda tr E I with E = (C - I)/2
  const double trE = 0.5 * (S(0, 0) + S(1, 1) + S(2, 2) - 3.0);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) S(i, j) *= m.mu;
    S(i, i) += -m.mu + m.lambda * trE;
  }
  P = F * S;
  return true;
}

/// psi(F) in the same closed forms, where closed_form_stress applies (false elsewhere).
KOKKOS_INLINE_FUNCTION bool closed_form_energy(const Material& m, const Mat3& F, double J,
                                               double& psi) {
  if (!closed_form_applies(m, F, J)) return false;
  if (m.model == Hyperelastic::neo_hookean) {
    const double log_j = math::log(J);
    const double f = frobenius(F);
    psi = 0.5 * m.mu * (f * f - 3.0) - m.mu * log_j + 0.5 * m.lambda * log_j * log_j;
    return true;
  }
  const Mat3 C = transpose(F) * F;
  double tr = 0.0, e2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    tr += 0.5 * (C(i, i) - 1.0);
    for (int j = 0; j < 3; ++j) {
      const double E = 0.5 * (C(i, j) - (i == j ? 1.0 : 0.0));
      e2 += E * E;
    }
  }
  psi = m.mu * e2 + 0.5 * m.lambda * tr * tr;
  return true;
}

}  // namespace amphora::kernels::solid

namespace amphora::kernels::solid {

/// The energy density matching diagonal_stress: below the clamp, the second-order expansion
/// psi(s*) + P^(s*) (s - s*) + (s - s*) dP^(s*) (s - s*) / 2 about the clamped point.
KOKKOS_INLINE_FUNCTION double diagonal_energy(const Material& m, const Vec3& s) {
  Vec3 c = s, d;
  bool clamped = false;
  for (int i = 0; i < 3; ++i)
    if (m.s_clamp > 0.0 && s[i] < m.s_clamp) c[i] = m.s_clamp, clamped = true;
  double e = diagonal_stress_detail::energy(m, c);
  if (!clamped) return e;
  const DiagonalStress r = diagonal_stress_detail::evaluate(m, c);
  for (int i = 0; i < 3; ++i) d[i] = s[i] - c[i];
  for (int i = 0; i < 3; ++i) {
    e += r.P[i] * d[i];
    for (int j = 0; j < 3; ++j) e += 0.5 * d[i] * r.dP_ds(i, j) * d[j];
  }
  return e;
}

}  // namespace amphora::kernels::solid
