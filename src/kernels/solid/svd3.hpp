#pragma once
// The 3x3 singular value decomposition F = U diag(s) V^T with rotations U and V (det +1) and
// Irving, Teran & Fedkiw's sign convention (SCA 2004, section 5): s_0 >= s_1 >= |s_2|, and s_2
// carries the sign of det F, so only the smallest-magnitude entry is negative when the element
// is inverted. Method: one-sided Jacobi rotations V make the columns of B = F V orthogonal
// (Demmel & Veselic 1992: high relative accuracy); B, its columns sorted by length, is factored
// B = U R by Gram-Schmidt with U's third column u_0 x u_1 (R is diagonal to round-off), so
// U diag(R) V^T reproduces F to round-off, singular F included. Runs on every backend.
#include "kernels/solid/mat3.hpp"

namespace amphora::kernels::solid {

struct Svd3 {
  Mat3 U, V;
  Vec3 s;  ///< the diagonal F^, s_0 >= s_1 >= |s_2|
};

namespace svd3_detail {

/// One Hestenes rotation of columns p, q of B (and V) making them orthogonal; false when they
/// already are to round-off relative to their lengths.
KOKKOS_INLINE_FUNCTION bool hestenes_rotate(Mat3& B, Mat3& V, int p, int q) {
  double alpha = 0.0, beta = 0.0, gamma = 0.0;
  for (int k = 0; k < 3; ++k) {
    alpha += B(k, p) * B(k, p);
    beta += B(k, q) * B(k, q);
    gamma += B(k, p) * B(k, q);
  }
  if (!(math::fabs(gamma) > 1e-15 * math::sqrt(alpha * beta))) return false;
  const double zeta = (beta - alpha) / (2.0 * gamma);
  const double az = math::fabs(zeta);
  double t = az > 1e150 ? 0.5 / az : 1.0 / (az + math::sqrt(zeta * zeta + 1.0));
  if (zeta < 0.0) t = -t;
  const double c = 1.0 / math::sqrt(t * t + 1.0), s = t * c;
  for (int k = 0; k < 3; ++k) {
    const double bp = B(k, p), bq = B(k, q), vp = V(k, p), vq = V(k, q);
    B(k, p) = c * bp - s * bq, B(k, q) = s * bp + c * bq;
    V(k, p) = c * vp - s * vq, V(k, q) = s * vp + c * vq;
  }
  return true;
}

/// One-sided (Hestenes) Jacobi: rotations V with B = F V of mutually orthogonal columns, to
/// round-off relative to each pair's lengths (so small singular values keep their accuracy,
/// which the eigenvectors of F^T F alone do not).
KOKKOS_INLINE_FUNCTION void orthogonalise_columns(Mat3& B, Mat3& V) {
  for (int sweep = 0; sweep < 20; ++sweep) {
    bool rotated = hestenes_rotate(B, V, 0, 1);
    rotated = hestenes_rotate(B, V, 0, 2) || rotated;
    rotated = hestenes_rotate(B, V, 1, 2) || rotated;
    if (!rotated) break;
  }
}

/// Swaps columns i and j of V and B and negates column j, keeping det V = +1.
KOKKOS_INLINE_FUNCTION void swap_columns(Mat3& V, Mat3& B, int i, int j) {
  for (int k = 0; k < 3; ++k) {
    const double v = V(k, i), b = B(k, i);
    V(k, i) = V(k, j), B(k, i) = B(k, j);
    V(k, j) = -v, B(k, j) = -b;
  }
}

/// A unit vector orthogonal to the unit vector u (for rank-deficient F).
KOKKOS_INLINE_FUNCTION Vec3 any_orthogonal(const Vec3& u) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (math::fabs(u[i]) < math::fabs(u[k])) k = i;
  Vec3 e;
  e[k] = 1.0;
  const Vec3 w = cross(u, e);
  const double n = norm(w);
  return Vec3{{w[0] / n, w[1] / n, w[2] / n}};
}

/// r minus its projection on the unit vector u.
KOKKOS_INLINE_FUNCTION Vec3 reject(Vec3 r, const Vec3& u) {
  const double p = dot(u, r);
  for (int i = 0; i < 3; ++i) r[i] -= p * u[i];
  return r;
}

}  // namespace svd3_detail

KOKKOS_INLINE_FUNCTION Svd3 svd3(const Mat3& F) {
  using namespace svd3_detail;
  Svd3 r;
  r.V = Mat3::identity();
  Mat3 B = F;
  orthogonalise_columns(B, r.V);
  double len[3];
  for (int j = 0; j < 3; ++j) len[j] = dot(B.column(j), B.column(j));
  // Sort by column length, largest first (three compare-and-swaps).
  const int pairs[3][2] = {{0, 1}, {1, 2}, {0, 1}};
  for (const auto& p : pairs)
    if (len[p[0]] < len[p[1]]) {
      swap_columns(r.V, B, p[0], p[1]);
      const double l = len[p[0]];
      len[p[0]] = len[p[1]], len[p[1]] = l;
    }
  // Gram-Schmidt (twice, for rank-deficient B) with u_2 = u_0 x u_1: U is a rotation.
  const Vec3 b0 = B.column(0), b1 = B.column(1), b2 = B.column(2);
  const double n0 = norm(b0);
  Vec3 u0;
  if (n0 > 0.0) {
    for (int i = 0; i < 3; ++i) u0[i] = b0[i] / n0;
  } else {
    u0[0] = 1.0;
  }
  const Vec3 w = reject(reject(b1, u0), u0);
  const double n1 = norm(w);
  Vec3 u1;
  if (n1 > 1e-14 * n0) {
    for (int i = 0; i < 3; ++i) u1[i] = w[i] / n1;
  } else {
    u1 = any_orthogonal(u0);
  }
  const Vec3 u2 = cross(u0, u1);
  r.U.set_column(0, u0), r.U.set_column(1, u1), r.U.set_column(2, u2);
  r.s = Vec3{{dot(u0, b0), dot(u1, b1), dot(u2, b2)}};
  if (r.s[1] < 0.0) {  // only possible for a vanishing s_1: move the sign to s_2
    for (int i = 0; i < 3; ++i) r.U(i, 1) = -r.U(i, 1), r.U(i, 2) = -r.U(i, 2);
    r.s[1] = -r.s[1], r.s[2] = -r.s[2];
  }
  return r;
}

}  // namespace amphora::kernels::solid
