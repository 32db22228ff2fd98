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

namespace amphora::sumfac {

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
};

/// One line: y[o ys] = sum_i M[o][i] x[i xs] (with `add`, +=). `sign` is m.sign when the
/// caller knows it at compile time (values +1, derivatives -1), 0 to read m.sign: a known sign
/// takes a test and branch out of every output pair of the hot sweeps. In place (x == y) is
/// allowed when n_rows == n_cols and xs == ys.
template <int n_rows, int n_cols, int xs, int ys, bool add, int sign = 0, class T>
KOKKOS_FORCEINLINE_FUNCTION void apply_even_odd_line(const EvenOddMatrix<n_rows, n_cols>& m, const T* xl, T* yl) {
  constexpr int hc = EvenOddMatrix<n_rows, n_cols>::half_cols;
  constexpr int hr = EvenOddMatrix<n_rows, n_cols>::half_rows;
  constexpr int hcs = hc > 0 ? hc : 1;
  const bool negate = sign == 0 ? m.sign < 0 : sign < 0;
  T e[hcs], d[hcs];
  for (int i = 0; i < hc; ++i) {
    e[i] = xl[i * xs] + xl[(n_cols - 1 - i) * xs];
    d[i] = xl[i * xs] - xl[(n_cols - 1 - i) * xs];
  }
  T mid = EvenOddMatrix<n_rows, n_cols>::has_middle_col ? xl[(n_cols / 2) * xs] : T(0.0);
  for (int o = 0; o < hr; ++o) {
    T ev = EvenOddMatrix<n_rows, n_cols>::has_middle_col ? T(m.middle[o]) * mid : T(0.0);
    T od = T(0.0);
    for (int i = 0; i < hc; ++i) {
      ev += T(m.even[o][i]) * e[i];
      od += T(m.odd[o][i]) * d[i];
    }
    if (2 * o + 1 == n_rows) {
      if (add) yl[o * ys] += ev + od;
      else yl[o * ys] = ev + od;
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

/// y = M x along one direction of a tensor of lines: line `p` (0 <= p < n_post) and offset `s`
/// (0 <= s < stride) reads x[(p n_cols + i) stride + s] and writes y[(p n_rows + o) stride + s].
/// With `add`, y += M x. In place (x == y) is allowed when n_rows == n_cols.
template <int n_rows, int n_cols, int stride, int n_post, bool add, int sign = 0, class T>
KOKKOS_FORCEINLINE_FUNCTION void apply_even_odd(const EvenOddMatrix<n_rows, n_cols>& m,
                                                const T* x, T* y) {
  for (int p = 0; p < n_post; ++p)
    for (int s = 0; s < stride; ++s)
      apply_even_odd_line<n_rows, n_cols, stride, stride, add, sign>(m, x + p * n_cols * stride + s,
                                                                      y + p * n_rows * stride + s);
}

}  // namespace amphora::sumfac
