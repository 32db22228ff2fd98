#pragma once
// 3x3 matrices and 3-vectors as plain structs for device code: the per-element algebra of
// the solid kernels (deformation gradients, stresses, shape matrices).
#include "kernels/kokkos_compat.hpp"

namespace amphora::kernels::solid {

struct Vec3 {
  double v[3] = {0.0, 0.0, 0.0};
  KOKKOS_INLINE_FUNCTION double& operator[](int i) { return v[i]; }
  KOKKOS_INLINE_FUNCTION double operator[](int i) const { return v[i]; }
};

/// a(i, j): row i, column j.
struct Mat3 {
  double a[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  KOKKOS_INLINE_FUNCTION double& operator()(int i, int j) { return a[i][j]; }
  KOKKOS_INLINE_FUNCTION double operator()(int i, int j) const { return a[i][j]; }
  KOKKOS_INLINE_FUNCTION static Mat3 identity() {
    Mat3 m;
    m(0, 0) = m(1, 1) = m(2, 2) = 1.0;
    return m;
  }
  KOKKOS_INLINE_FUNCTION static Mat3 diagonal(const Vec3& d) {
    Mat3 m;
    for (int i = 0; i < 3; ++i) m(i, i) = d[i];
    return m;
  }
  KOKKOS_INLINE_FUNCTION Vec3 column(int j) const { return Vec3{{a[0][j], a[1][j], a[2][j]}}; }
  KOKKOS_INLINE_FUNCTION void set_column(int j, const Vec3& c) {
    for (int i = 0; i < 3; ++i) a[i][j] = c[i];
  }
};

KOKKOS_INLINE_FUNCTION double dot(const Vec3& x, const Vec3& y) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}
KOKKOS_INLINE_FUNCTION Vec3 cross(const Vec3& x, const Vec3& y) {
  return Vec3{{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]}};
}
KOKKOS_INLINE_FUNCTION double norm(const Vec3& x) { return math::sqrt(dot(x, x)); }

KOKKOS_INLINE_FUNCTION Mat3 operator*(const Mat3& x, const Mat3& y) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = x(i, 0) * y(0, j) + x(i, 1) * y(1, j) + x(i, 2) * y(2, j);
  return r;
}
KOKKOS_INLINE_FUNCTION Mat3 transpose(const Mat3& x) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = x(j, i);
  return r;
}
KOKKOS_INLINE_FUNCTION double determinant(const Mat3& m) {
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) -
         m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
}
/// The inverse by cofactors (the caller checks the determinant).
KOKKOS_INLINE_FUNCTION Mat3 inverse(const Mat3& m) {
  Mat3 c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      c(j, i) = m(i1, j1) * m(i2, j2) - m(i1, j2) * m(i2, j1);  // the adjugate, transposed
    }
  const double inv_det = 1.0 / determinant(m);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c(i, j) *= inv_det;
  return c;
}
/// Frobenius norm.
KOKKOS_INLINE_FUNCTION double frobenius(const Mat3& m) {
  double s = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s += m(i, j) * m(i, j);
  return math::sqrt(s);
}

}  // namespace amphora::kernels::solid
