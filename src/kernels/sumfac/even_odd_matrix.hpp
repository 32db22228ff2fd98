#pragma once
// A 1D interpolation or derivative matrix M (n_rows x n_cols) between point sets that are
// symmetric about 1/2, stored in even–odd form: M[n_rows-1-o][n_cols-1-i] = s M[o][i] with
// s = +1 (values) or -1 (derivatives) lets one product of a line serve two outputs, halving the
// multiplications (Kronbichler & Kormann, ACM TOMS 45(3), 2019, sec. 3.2; Solomonoff 1992).
// Plain fixed-size arrays: the struct is copied into kernels by value.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

namespace amphora::kernels::sumfac {

template <int n_rows, int n_cols>
struct EvenOddMatrix {
  static constexpr int half_rows = (n_rows + 1) / 2;  ///< rows computed (the rest mirrored)
  static constexpr int half_cols = n_cols / 2;        ///< column pairs
  static constexpr bool has_middle_col = (n_cols % 2) == 1;
  double even[half_rows][half_cols > 0 ? half_cols : 1];
  double odd[half_rows][half_cols > 0 ? half_cols : 1];
  double middle[half_rows];  ///< M[o][n_cols/2] when n_cols is odd
  int sign = 1;

  /// From a dense row-major matrix; throws if it does not have the symmetry `s`.
  static EvenOddMatrix from_dense(const std::vector<double>& m, int s) {
    if (static_cast<int>(m.size()) != n_rows * n_cols)
      throw std::invalid_argument("EvenOddMatrix: wrong matrix size");
    EvenOddMatrix r{};
    r.sign = s;
    double scale = 0.0;
    for (double v : m) scale = std::max(scale, std::abs(v));
    for (int o = 0; o < n_rows; ++o)
      for (int i = 0; i < n_cols; ++i) {
        const double a = m[o * n_cols + i], b = m[(n_rows - 1 - o) * n_cols + (n_cols - 1 - i)];
        if (std::abs(b - s * a) > 1e-11 * scale + 1e-13)
          throw std::invalid_argument("EvenOddMatrix: matrix lacks the even-odd symmetry");
      }
    for (int o = 0; o < half_rows; ++o) {
      for (int i = 0; i < half_cols; ++i) {
        const double a = m[o * n_cols + i], b = m[o * n_cols + n_cols - 1 - i];
        r.even[o][i] = 0.5 * (a + b);
        r.odd[o][i] = 0.5 * (a - b);
      }
      r.middle[o] = has_middle_col ? m[o * n_cols + n_cols / 2] : 0.0;
    }
    return r;
  }

  /// The dense row-major matrix, M[o * n_cols + i], into out (n_rows * n_cols entries).
  KOKKOS_INLINE_FUNCTION void to_dense(double* out) const {
    for (int o = 0; o < half_rows; ++o) {
      for (int i = 0; i < half_cols; ++i) {
        out[o * n_cols + i] = even[o][i] + odd[o][i];
        out[o * n_cols + n_cols - 1 - i] = even[o][i] - odd[o][i];
      }
      if (has_middle_col) out[o * n_cols + n_cols / 2] = middle[o];
    }
    for (int o = half_rows; o < n_rows; ++o)
      for (int i = 0; i < n_cols; ++i)
        out[o * n_cols + i] = sign * out[(n_rows - 1 - o) * n_cols + n_cols - 1 - i];
  }
};

/// The even and odd parts of a line of n entries at stride xs, which every product with an
/// even-odd matrix starts from: e[i] = x_i + x_(n-1-i), d[i] = x_i - x_(n-1-i) for i < n / 2,
/// and the middle entry (zero for even n).
template <int n, int xs, class T>
KOKKOS_FORCEINLINE_FUNCTION void even_odd_parts(const T* xl, T* e, T* d, T& mid) {
  for (int i = 0; i < n / 2; ++i) {
    e[i] = xl[i * xs] + xl[(n - 1 - i) * xs];
    d[i] = xl[i * xs] - xl[(n - 1 - i) * xs];
  }
  mid = n % 2 == 1 ? xl[(n / 2) * xs] : T(0.0);
}

/// One line: y[o ys] = sum_i M[o][i] x[i xs] (with `add`, +=). `sign` is m.sign when the
/// caller knows it at compile time (values +1, derivatives -1), 0 to read m.sign: a known sign
/// takes a test and branch out of every output pair of the hot sweeps. In place (x == y) is
/// allowed when n_rows == n_cols and xs == ys.
template <int n_rows, int n_cols, int xs, int ys, bool add, int sign = 0, class T>
KOKKOS_FORCEINLINE_FUNCTION void apply_even_odd_line(const EvenOddMatrix<n_rows, n_cols>& m,
                                                     const T* xl, T* yl) {
  constexpr int hc = EvenOddMatrix<n_rows, n_cols>::half_cols;
  constexpr int hr = EvenOddMatrix<n_rows, n_cols>::half_rows;
  constexpr int hcs = hc > 0 ? hc : 1;
  const bool negate = sign == 0 ? m.sign < 0 : sign < 0;
  T e[hcs], d[hcs], mid;
  even_odd_parts<n_cols, xs>(xl, e, d, mid);
  for (int o = 0; o < hr; ++o) {
    T ev = EvenOddMatrix<n_rows, n_cols>::has_middle_col ? T(m.middle[o]) * mid : T(0.0);
    T od = T(0.0);
    for (int i = 0; i < hc; ++i) {
      ev += T(m.even[o][i]) * e[i];
      od += T(m.odd[o][i]) * d[i];
    }
    if (2 * o + 1 == n_rows) {
      if (add)
        yl[o * ys] += ev + od;
      else
        yl[o * ys] = ev + od;
    } else {
      const T lo = ev + od, hi = negate ? od - ev : ev - od;
      if (add) {
        yl[o * ys] += lo;
        yl[(n_rows - 1 - o) * ys] += hi;
      } else {
        yl[o * ys] = lo;
        yl[(n_rows - 1 - o) * ys] = hi;
      }
    }
  }
}

/// One line through two square matrices of the same (+1) symmetry at once, sharing the even
/// and odd parts of x: y1 = s1 (A x), y2 = s2 (B x) (with `add2`, y2 += ...). x may not alias
/// y1 or y2.
template <int n, int xs, int ys, bool add2, class T>
KOKKOS_FORCEINLINE_FUNCTION void apply_even_odd_pair_line(const EvenOddMatrix<n, n>& a,
                                                          const EvenOddMatrix<n, n>& b, const T* xl,
                                                          T* y1, T* y2, T s1, T s2) {
  using M = EvenOddMatrix<n, n>;
  constexpr int hc = M::half_cols, hr = M::half_rows, hcs = hc > 0 ? hc : 1;
  T e[hcs], d[hcs], mid;
  even_odd_parts<n, xs>(xl, e, d, mid);
  for (int o = 0; o < hr; ++o) {
    T ea = M::has_middle_col ? T(a.middle[o]) * mid : T(0.0), oa = T(0.0);
    T eb = M::has_middle_col ? T(b.middle[o]) * mid : T(0.0), ob = T(0.0);
    for (int i = 0; i < hc; ++i) {
      ea += T(a.even[o][i]) * e[i];
      oa += T(a.odd[o][i]) * d[i];
      eb += T(b.even[o][i]) * e[i];
      ob += T(b.odd[o][i]) * d[i];
    }
    const T lo1 = s1 * (ea + oa), lo2 = s2 * (eb + ob);
    if (add2)
      y2[o * ys] += lo2;
    else
      y2[o * ys] = lo2;
    y1[o * ys] = lo1;
    if (2 * o + 1 != n) {
      const T hi1 = s1 * (ea - oa), hi2 = s2 * (eb - ob);
      y1[(n - 1 - o) * ys] = hi1;
      if (add2)
        y2[(n - 1 - o) * ys] += hi2;
      else
        y2[(n - 1 - o) * ys] = hi2;
    }
  }
}

/// y = A x1 + B x2 for one line of each, A and B square with +1 symmetry. In place (y == x1 or
/// y == x2) is allowed: both lines are read whole before y is written.
template <int n, int s, class T>
KOKKOS_FORCEINLINE_FUNCTION void apply_even_odd_sum_line(const EvenOddMatrix<n, n>& a, const T* x1,
                                                         const EvenOddMatrix<n, n>& b, const T* x2,
                                                         T* y) {
  using M = EvenOddMatrix<n, n>;
  constexpr int hc = M::half_cols, hr = M::half_rows, hcs = hc > 0 ? hc : 1;
  T e1[hcs], d1[hcs], m1, e2[hcs], d2[hcs], m2;
  even_odd_parts<n, s>(x1, e1, d1, m1);
  even_odd_parts<n, s>(x2, e2, d2, m2);
  for (int o = 0; o < hr; ++o) {
    T ev = M::has_middle_col ? T(a.middle[o]) * m1 + T(b.middle[o]) * m2 : T(0.0), od = T(0.0);
    for (int i = 0; i < hc; ++i) {
      ev += T(a.even[o][i]) * e1[i] + T(b.even[o][i]) * e2[i];
      od += T(a.odd[o][i]) * d1[i] + T(b.odd[o][i]) * d2[i];
    }
    y[o * s] = ev + od;
    if (2 * o + 1 != n) y[(n - 1 - o) * s] = ev - od;
  }
}

/// y = M x along one direction of a tensor of lines: line `p` (0 <= p < n_post) and offset `s`
/// (0 <= s < stride) reads x[(p n_cols + i) stride + s] and writes y[(p n_rows + o) stride + s].
/// With `add`, y += M x. In place (x == y) is allowed when n_rows == n_cols.
template <int n_rows, int n_cols, int stride, int n_post, bool add, int sign = 0, class T>
KOKKOS_FORCEINLINE_FUNCTION void apply_even_odd(const EvenOddMatrix<n_rows, n_cols>& m, const T* x,
                                                T* y) {
  for (int p = 0; p < n_post; ++p)
    for (int s = 0; s < stride; ++s)
      apply_even_odd_line<n_rows, n_cols, stride, stride, add, sign>(m, x + p * n_cols * stride + s,
                                                                     y + p * n_rows * stride + s);
}

}  // namespace amphora::kernels::sumfac
