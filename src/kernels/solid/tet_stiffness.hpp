#pragma once
// The stiffness of the linear-tetrahedron forces for Newton's method (Teran, Sifakis, Irving &
// Fedkiw, SCA 2005, section 5). With F = U F^ V^T, dP = U [dP^/dF^ : (U^T dF V)] V^T, and for
// an isotropic model dP^/dF^ is block diagonal: the 3x3 block dP^_i/ds_j on the diagonal
// entries and, on each off-diagonal pair (dF^_ij, dF^_ji), [[a, b], [b, a]] with eigenvalues
// a + b = (P^_i - P^_j)/(s_i - s_j) on (1, 1) and a - b = (P^_i + P^_j)/(s_i + s_j) on (1, -1).
// With `definite`, every block's negative eigenvalues are set to zero: K is then symmetric
// positive semi-definite at any F, inverted included (the definite part of the Hessian).
// K dx = W dP D_m^-T per element (the negated force differential), scattered with atomics.
#include "kernels/solid/tet_forces.hpp"

namespace amphora::kernels::solid {

/// The factors of K at one configuration: U, V and the diagonal-space blocks per element.
template <class MemSpace>
struct TetStiffness {
  Kokkos::View<double*[3][3], MemSpace> U, V;
  Kokkos::View<double* [3][3], MemSpace> A;     ///< dP^_i/ds_j (made definite where asked)
  Kokkos::View<double* [3][2], MemSpace> pair;  ///< a + b, a - b for (0,1), (0,2), (1,2)
};

namespace stiffness_detail {

/// The off-diagonal pairs (0, 1), (0, 2), (1, 2) (functions: device code cannot read a
/// namespace-scope array).
KOKKOS_INLINE_FUNCTION int pair_i(int p) { return p == 2 ? 1 : 0; }
KOKKOS_INLINE_FUNCTION int pair_j(int p) { return p == 0 ? 1 : 2; }

/// Q diag(max(lambda, 0)) Q^T of a symmetric 3x3 matrix (cyclic Jacobi eigen-iterations).
KOKKOS_INLINE_FUNCTION Mat3 positive_part(Mat3 A) {
  Mat3 Q = Mat3::identity();
  for (int sweep = 0; sweep < 12; ++sweep) {
    double off = 0.0;
    for (int p = 0; p < 3; ++p) off += A(pair_i(p), pair_j(p)) * A(pair_i(p), pair_j(p));
    if (!(off > 1e-30 * (A(0, 0) * A(0, 0) + A(1, 1) * A(1, 1) + A(2, 2) * A(2, 2)))) break;
    for (int pq = 0; pq < 3; ++pq) {
      const int p = pair_i(pq), q = pair_j(pq);
      if (A(p, q) == 0.0) continue;
      const double theta = (A(q, q) - A(p, p)) / (2.0 * A(p, q));
      const double t =
          (theta >= 0.0 ? 1.0 : -1.0) / (math::fabs(theta) + math::sqrt(theta * theta + 1.0));
      const double c = 1.0 / math::sqrt(t * t + 1.0), s = t * c;
      for (int k = 0; k < 3; ++k) {  // A <- A J, then A <- J^T A; Q <- Q J
        const double akp = A(k, p), akq = A(k, q);
        A(k, p) = c * akp - s * akq, A(k, q) = s * akp + c * akq;
      }
      for (int k = 0; k < 3; ++k) {
        const double apk = A(p, k), aqk = A(q, k);
        A(p, k) = c * apk - s * aqk, A(q, k) = s * apk + c * aqk;
      }
      for (int k = 0; k < 3; ++k) {
        const double qkp = Q(k, p), qkq = Q(k, q);
        Q(k, p) = c * qkp - s * qkq, Q(k, q) = s * qkp + c * qkq;
      }
    }
  }
  Mat3 R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) R(i, j) += Q(i, k) * (A(k, k) > 0.0 ? A(k, k) : 0.0) * Q(j, k);
  return R;
}

/// (P_i - P_j)/(s_i - s_j), by its limit dP_i/ds_i - dP_i/ds_j where s_i and s_j coincide.
KOKKOS_INLINE_FUNCTION double difference_quotient(const DiagonalStress& d, const Vec3& s, int i,
                                                  int j) {
  const double ds = s[i] - s[j];
  if (math::fabs(ds) > 1e-8 * (math::fabs(s[i]) + math::fabs(s[j]) + 1e-300))
    return (d.P[i] - d.P[j]) / ds;
  return d.dP_ds(i, i) - d.dP_ds(i, j);
}

/// (P_i + P_j)/(s_i + s_j) with the denominator kept at least 1e-6 in magnitude (Teran et al.).
KOKKOS_INLINE_FUNCTION double sum_quotient(const DiagonalStress& d, const Vec3& s, int i, int j) {
  double den = s[i] + s[j];
  if (math::fabs(den) < 1e-6) den = den < 0.0 ? -1e-6 : 1e-6;
  return (d.P[i] + d.P[j]) / den;
}

/// dP for dF at element e from the stored factors.
template <class MemSpace>
KOKKOS_INLINE_FUNCTION Mat3 stress_differential(const TetStiffness<MemSpace>& k, int e,
                                                const Mat3& dF) {
  const Mat3 U = tet_detail::load(k.U, e), V = tet_detail::load(k.V, e),
             A = tet_detail::load(k.A, e);
  const Mat3 G = transpose(U) * dF * V;  // dF^
  Mat3 dPh;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) dPh(i, i) += A(i, j) * G(j, j);
  for (int p = 0; p < 3; ++p) {
    const int i = pair_i(p), j = pair_j(p);
    const double sym = 0.5 * (G(i, j) + G(j, i)), skew = 0.5 * (G(i, j) - G(j, i));
    dPh(i, j) = k.pair(e, p, 0) * sym + k.pair(e, p, 1) * skew;
    dPh(j, i) = k.pair(e, p, 0) * sym - k.pair(e, p, 1) * skew;
  }
  return U * dPh * transpose(V);
}

}  // namespace stiffness_detail

template <class MemSpace>
TetStiffness<MemSpace> allocate_stiffness(int n_tets) {
  return {Kokkos::View<double* [3][3], MemSpace>("solid::K::U", n_tets),
          Kokkos::View<double* [3][3], MemSpace>("solid::K::V", n_tets),
          Kokkos::View<double* [3][3], MemSpace>("solid::K::A", n_tets),
          Kokkos::View<double* [3][2], MemSpace>("solid::K::pair", n_tets)};
}

/// The factors of K at positions x, and diag(i, d) += the diagonal of K (a Jacobi
/// preconditioner's).
template <class ExecSpace, class MemSpace>
void tet_stiffness(const ExecSpace& exec, const Material& m, const TetRestShapes<MemSpace>& rest,
                   const Kokkos::View<int* [4], MemSpace>& tets,
                   const Kokkos::View<double* [3], MemSpace>& x, bool definite,
                   const TetStiffness<MemSpace>& k,
                   const Kokkos::View<double* [3], MemSpace>& diag) {
  const auto Dm_inv = rest.Dm_inv;
  const auto volume = rest.volume;
  Kokkos::parallel_for(
      "amphora::solid::tet_stiffness", RangePolicy<ExecSpace>(exec, 0, int(tets.extent(0))),
      KOKKOS_LAMBDA(const int e) {
        const Mat3 Bm = tet_detail::load(Dm_inv, e);
        const Svd3 d = svd3(tet_detail::edge_matrix(x, tets, e) * Bm);
        const DiagonalStress ps = diagonal_stress(m, d.s);
        Mat3 A = ps.dP_ds;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < i; ++j) A(i, j) = A(j, i) = 0.5 * (A(i, j) + A(j, i));
        if (definite) A = stiffness_detail::positive_part(A);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            k.U(e, i, j) = d.U(i, j), k.V(e, i, j) = d.V(i, j), k.A(e, i, j) = A(i, j);
        for (int p = 0; p < 3; ++p) {
          const int i = stiffness_detail::pair_i(p), j = stiffness_detail::pair_j(p);
          double plus = stiffness_detail::difference_quotient(ps, d.s, i, j);
          double minus = stiffness_detail::sum_quotient(ps, d.s, i, j);
          if (definite) plus = plus > 0.0 ? plus : 0.0, minus = minus > 0.0 ? minus : 0.0;
          k.pair(e, p, 0) = plus, k.pair(e, p, 1) = minus;
        }
        // Node c's shape gradient g_c (rows of D_m^-1; g_0 = -their sum); K's diagonal entry
        // for (c, dir) is W (g_c^T dP(e_dir g_c^T)^T e_dir) = W dP(e_dir g_c^T)_dir . g_c.
        for (int c = 0; c < 4; ++c)
          for (int dir = 0; dir < 3; ++dir) {
            Mat3 dF;
            for (int j = 0; j < 3; ++j)
              dF(dir, j) = c == 0 ? -(Bm(0, j) + Bm(1, j) + Bm(2, j)) : Bm(c - 1, j);
            const Mat3 dP = stiffness_detail::stress_differential(k, e, dF);
            double entry = 0.0;
            for (int j = 0; j < 3; ++j) entry += dP(dir, j) * dF(dir, j);
            Kokkos::atomic_add(&diag(tets(e, c), dir), volume(e) * entry);
          }
      });
}

/// out += K dx (the negated force differential) with the factors k.
template <class ExecSpace, class MemSpace>
void tet_stiffness_apply(const ExecSpace& exec, const TetRestShapes<MemSpace>& rest,
                         const Kokkos::View<int* [4], MemSpace>& tets,
                         const TetStiffness<MemSpace>& k,
                         const Kokkos::View<double* [3], MemSpace>& dx,
                         const Kokkos::View<double* [3], MemSpace>& out) {
  const auto Dm_inv = rest.Dm_inv;
  const auto volume = rest.volume;
  Kokkos::parallel_for(
      "amphora::solid::tet_stiffness_apply", RangePolicy<ExecSpace>(exec, 0, int(tets.extent(0))),
      KOKKOS_LAMBDA(const int e) {
        const Mat3 Bm = tet_detail::load(Dm_inv, e);
        const Mat3 dF = tet_detail::edge_matrix(dx, tets, e) * Bm;
        const Mat3 H = stiffness_detail::stress_differential(k, e, dF) * transpose(Bm);
        tet_detail::scatter(out, tets, e, volume(e), H);
      });
}

}  // namespace amphora::kernels::solid
