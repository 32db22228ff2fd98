#pragma once
// Linear-tetrahedron elastic forces (Irving, Teran & Fedkiw, SCA 2004, section 4): per element
// F = D_s D_m^-1 from the current and rest edge matrices, F = U F^ V^T (svd3), P = U P^(F^) V^T
// (diagonal_stress; in closed form without the SVD where no singular value is near the clamp),
// and the nodal forces [f_1 f_2 f_3] = -W P D_m^-T, f_0 = -(f_1 + f_2 + f_3),
// scattered with atomics. The rest data (D_m^-1, W) are computed once by tet_rest_shapes.
// Kelvin-Voigt damping forces (a viscous stress on the rate of C = F^T F) likewise.
#include "kernels/solid/diagonal_stress.hpp"
#include "kernels/solid/svd3.hpp"
#include "kernels/spaces.hpp"

namespace amphora::kernels::solid {

template <class MemSpace>
struct TetRestShapes {
  Kokkos::View<double* [3][3], MemSpace> Dm_inv;  ///< inverse rest edge matrix per element
  Kokkos::View<double*, MemSpace> volume;         ///< signed rest volume det(D_m)/6
};

namespace tet_detail {

/// The edge matrix [x_1 - x_0, x_2 - x_0, x_3 - x_0] of element e.
template <class Nodes, class Tets>
KOKKOS_INLINE_FUNCTION Mat3 edge_matrix(const Nodes& x, const Tets& tets, int e) {
  Mat3 D;
  const int n0 = tets(e, 0);
  for (int c = 1; c < 4; ++c)
    for (int i = 0; i < 3; ++i) D(i, c - 1) = x(tets(e, c), i) - x(n0, i);
  return D;
}

/// Element e's 3x3 block of a per-element View.
template <class MemSpace>
KOKKOS_INLINE_FUNCTION Mat3 load(const Kokkos::View<double* [3][3], MemSpace>& v, int e) {
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = v(e, i, j);
  return m;
}

/// v(e) = m.
template <class MemSpace>
KOKKOS_INLINE_FUNCTION void store(const Kokkos::View<double* [3][3], MemSpace>& v, int e,
                                  const Mat3& m) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) v(e, i, j) = m(i, j);
}

/// out += s H e_c at node c = 1, 2, 3 of element e and minus their sum at node 0 (atomics).
template <class Nodes, class Tets>
KOKKOS_INLINE_FUNCTION void scatter(const Nodes& out, const Tets& tets, int e, double s,
                                    const Mat3& H) {
  for (int i = 0; i < 3; ++i) {
    double o0 = 0.0;
    for (int c = 1; c < 4; ++c) {
      const double v = s * H(i, c - 1);
      Kokkos::atomic_add(&out(tets(e, c), i), v);
      o0 -= v;
    }
    Kokkos::atomic_add(&out(tets(e, 0), i), o0);
  }
}

}  // namespace tet_detail

/// D_m^-1 and the signed rest volumes; elements with volume <= 0 are the caller's to refuse.
template <class ExecSpace, class MemSpace>
TetRestShapes<MemSpace> tet_rest_shapes(const ExecSpace& exec,
                                        const Kokkos::View<double* [3], MemSpace>& X,
                                        const Kokkos::View<int* [4], MemSpace>& tets) {
  const int n = static_cast<int>(tets.extent(0));
  TetRestShapes<MemSpace> r{Kokkos::View<double* [3][3], MemSpace>("solid::Dm_inv", n),
                            Kokkos::View<double*, MemSpace>("solid::volume", n)};
  const auto Dm_inv = r.Dm_inv;
  const auto volume = r.volume;
  Kokkos::parallel_for(
      "amphora::solid::tet_rest_shapes", RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(const int e) {
        const Mat3 D = tet_detail::edge_matrix(X, tets, e);
        const double det = determinant(D);
        volume(e) = det / 6.0;
        const Mat3 inv = det != 0.0 ? inverse(D) : Mat3();
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) Dm_inv(e, i, j) = inv(i, j);
      });
  return r;
}

/// f += the elastic forces at positions x; J(e) = det F per element. Forces of inverted
/// elements are finite only with m.s_clamp > 0 (the invertible model).
template <class ExecSpace, class MemSpace>
void tet_forces(const ExecSpace& exec, const Material& m, const TetRestShapes<MemSpace>& rest,
                const Kokkos::View<int* [4], MemSpace>& tets,
                const Kokkos::View<double* [3], MemSpace>& x,
                const Kokkos::View<double* [3], MemSpace>& f,
                const Kokkos::View<double*, MemSpace>& J) {
  const auto Dm_inv = rest.Dm_inv;
  const auto volume = rest.volume;
  Kokkos::parallel_for(
      "amphora::solid::tet_forces", RangePolicy<ExecSpace>(exec, 0, int(tets.extent(0))),
      KOKKOS_LAMBDA(const int e) {
        const Mat3 Bm = tet_detail::load(Dm_inv, e);
        const Mat3 F = tet_detail::edge_matrix(x, tets, e) * Bm;
        const double j = determinant(F);
        J(e) = j;
        Mat3 P;
        if (!closed_form_stress(m, F, j, P)) {
          const Svd3 d = svd3(F);
          const DiagonalStress ps = diagonal_stress(m, d.s);
          P = d.U * Mat3::diagonal(ps.P) * transpose(d.V);
        }
        const Mat3 H = P * transpose(Bm);  // f_c = -W H e_c
        tet_detail::scatter(f, tets, e, -volume(e), H);
      });
}

/// f += the Kelvin-Voigt damping forces of viscosity eta at positions x and velocities v:
/// the second Piola-Kirchhoff stress S = eta dC/dt, dC/dt = dF^T F + F^T dF with
/// dF = V_s D_m^-1 (V_s the velocity edge matrix), P = F S, [f_1 f_2 f_3] = -W P D_m^-T. A rigid
/// motion has dC/dt = 0 (no force); the dissipation P : dF = eta/2 |dC/dt|^2 >= 0.
template <class ExecSpace, class MemSpace>
void tet_damping_forces(const ExecSpace& exec, double eta, const TetRestShapes<MemSpace>& rest,
                        const Kokkos::View<int* [4], MemSpace>& tets,
                        const Kokkos::View<double* [3], MemSpace>& x,
                        const Kokkos::View<double* [3], MemSpace>& v,
                        const Kokkos::View<double* [3], MemSpace>& f) {
  const auto Dm_inv = rest.Dm_inv;
  const auto volume = rest.volume;
  Kokkos::parallel_for(
      "amphora::solid::tet_damping_forces", RangePolicy<ExecSpace>(exec, 0, int(tets.extent(0))),
      KOKKOS_LAMBDA(const int e) {
        const Mat3 Bm = tet_detail::load(Dm_inv, e);
        const Mat3 F = tet_detail::edge_matrix(x, tets, e) * Bm;
        const Mat3 dF = tet_detail::edge_matrix(v, tets, e) * Bm;
        const Mat3 FtdF = transpose(F) * dF;
        Mat3 S;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) S(i, j) = eta * (FtdF(i, j) + FtdF(j, i));
        const Mat3 H = F * S * transpose(Bm);  // f_c = -W H e_c
        tet_detail::scatter(f, tets, e, -volume(e), H);
      });
}

/// The elastic energy sum_e W_e psi(F^_e) at positions x.
template <class ExecSpace, class MemSpace>
double tet_elastic_energy(const ExecSpace& exec, const Material& m,
                          const TetRestShapes<MemSpace>& rest,
                          const Kokkos::View<int* [4], MemSpace>& tets,
                          const Kokkos::View<double* [3], MemSpace>& x) {
  const auto Dm_inv = rest.Dm_inv;
  const auto volume = rest.volume;
  double energy = 0.0;
  Kokkos::parallel_reduce(
      "amphora::solid::tet_elastic_energy", RangePolicy<ExecSpace>(exec, 0, int(tets.extent(0))),
      KOKKOS_LAMBDA(const int e, double& sum) {
        const Mat3 Bm = tet_detail::load(Dm_inv, e);
        const Mat3 F = tet_detail::edge_matrix(x, tets, e) * Bm;
        double psi = 0.0;
        if (!closed_form_energy(m, F, determinant(F), psi)) psi = diagonal_energy(m, svd3(F).s);
        sum += volume(e) * psi;
      },
      energy);
  return energy;
}

}  // namespace amphora::kernels::solid
