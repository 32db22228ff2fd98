#pragma once
// Multiplicative plasticity for the linear-tetrahedron solid (Irving, Teran & Fedkiw, SCA 2004,
// section 6): F = F_e F_p per element, the elastic model evaluated at F_e = D_s (F_p D_m)^-1,
// so a plastic update only rewrites the element's inverse rest edge matrix D_m^-1 F_p^-1.
// After a step, the deviatoric Hencky strain of F_e = U F^ V^T beyond the yield strain flows
// into F_p (volume preserving: det F_p = 1), and F_p's own Hencky strain is clamped to log c
// so no element's rest shape becomes arbitrarily ill-conditioned. Inverted elements do not flow.
#include "kernels/solid/svd3.hpp"
#include "kernels/solid/tet_forces.hpp"

namespace amphora::kernels::solid {

struct PlasticFlow {
  double yield = 0.0;  ///< the Frobenius norm of the deviatoric Hencky strain at yield; 0: off
  double clamp = 3.0;  ///< F_p's singular values stay in [1/clamp, clamp] (its Hencky norm)
};

namespace plastic_detail {

/// V diag(exp(e)) V^T.
KOKKOS_INLINE_FUNCTION Mat3 exp_in_frame(const Mat3& V, const Vec3& e) {
  const Vec3 s{{math::exp(e[0]), math::exp(e[1]), math::exp(e[2])}};
  return V * Mat3::diagonal(s) * transpose(V);
}

/// The deviatoric part of v and its Frobenius norm.
KOKKOS_INLINE_FUNCTION double deviator(Vec3& v) {
  const double mean = (v[0] + v[1] + v[2]) / 3.0;
  for (int i = 0; i < 3; ++i) v[i] -= mean;
  return norm(v);
}

}  // namespace plastic_detail

/// The new F_p after the flow of F_e (= F F_p^-1): F_p unchanged within the yield surface or
/// under inversion; otherwise F_p' = V exp(g dev e) V^T F_p with e = log F^ and g the fraction
/// of dev e beyond the yield (return to the surface), then F_p' = U_p exp(dev e_p) V_p^T with its
/// Hencky strain e_p scaled down to norm log(clamp) where it is longer.
KOKKOS_INLINE_FUNCTION Mat3 plastic_update(const PlasticFlow& p, const Mat3& Fe, const Mat3& Fp) {
  const Svd3 d = svd3(Fe);
  if (!(d.s[2] > 0.0)) return Fp;
  Vec3 e{{math::log(d.s[0]), math::log(d.s[1]), math::log(d.s[2])}};
  const double n = plastic_detail::deviator(e);
  if (!(n > p.yield)) return Fp;
  const double g = (n - p.yield) / n;
  const Vec3 flow{{g * e[0], g * e[1], g * e[2]}};
  const Mat3 Fp_new = plastic_detail::exp_in_frame(d.V, flow) * Fp;
  const Svd3 q = svd3(Fp_new);
  Vec3 ep{{math::log(q.s[0]), math::log(q.s[1]), math::log(q.s[2])}};
  const double np = plastic_detail::deviator(ep), limit = math::log(p.clamp);
  if (np > limit)
    for (int i = 0; i < 3; ++i) ep[i] *= limit / np;
  const Vec3 sp{{math::exp(ep[0]), math::exp(ep[1]), math::exp(ep[2])}};
  return q.U * Mat3::diagonal(sp) * transpose(q.V);
}

/// The forces' D_m^-1 = Dm0_inv F_p^-1 from F_p (after a flow, and on a restart).
template <class ExecSpace, class MemSpace>
void tet_plastic_rest_shapes(const ExecSpace& exec,
                             const Kokkos::View<double* [3][3], MemSpace>& Dm0_inv,
                             const Kokkos::View<double* [3][3], MemSpace>& Fp,
                             const Kokkos::View<double* [3][3], MemSpace>& Dm_inv) {
  Kokkos::parallel_for(
      "amphora::solid::tet_plastic_rest_shapes", RangePolicy<ExecSpace>(exec, 0, int(Fp.extent(0))),
      KOKKOS_LAMBDA(const int e) {
        const Mat3 B = tet_detail::load(Dm0_inv, e) * inverse(tet_detail::load(Fp, e));
        tet_detail::store(Dm_inv, e, B);
      });
}

/// The plastic flow of every element at positions x: F_p updated (plastic_update) and the
/// forces' D_m^-1 rewritten as Dm0_inv F_p^-1 (Dm0_inv: the mesh's own rest shapes).
template <class ExecSpace, class MemSpace>
void tet_plastic_flow(const ExecSpace& exec, const PlasticFlow& p,
                      const Kokkos::View<double* [3][3], MemSpace>& Dm0_inv,
                      const Kokkos::View<int* [4], MemSpace>& tets,
                      const Kokkos::View<double* [3], MemSpace>& x,
                      const Kokkos::View<double* [3][3], MemSpace>& Fp,
                      const Kokkos::View<double* [3][3], MemSpace>& Dm_inv) {
  Kokkos::parallel_for(
      "amphora::solid::tet_plastic_flow", RangePolicy<ExecSpace>(exec, 0, int(tets.extent(0))),
      KOKKOS_LAMBDA(const int e) {
        const Mat3 Fe = tet_detail::edge_matrix(x, tets, e) * tet_detail::load(Dm_inv, e);
        tet_detail::store(Fp, e, plastic_update(p, Fe, tet_detail::load(Fp, e)));
      });
  // D_m^-1 by its own kernel: a restart (F_p read back) then rebuilds it bit for bit
  tet_plastic_rest_shapes(exec, Dm0_inv, Fp, Dm_inv);
}

/// The largest Hencky strain norm |log F^_p| over the elements.
template <class ExecSpace, class MemSpace>
double max_plastic_strain(const ExecSpace& exec, const Kokkos::View<double* [3][3], MemSpace>& Fp) {
  double m = 0.0;
  Kokkos::parallel_reduce(
      "amphora::solid::max_plastic_strain", RangePolicy<ExecSpace>(exec, 0, int(Fp.extent(0))),
      KOKKOS_LAMBDA(const int e, double& acc) {
        const Svd3 q = svd3(tet_detail::load(Fp, e));
        const Vec3 ep{{math::log(q.s[0]), math::log(q.s[1]), math::log(q.s[2])}};
        const double n = norm(ep);
        acc = n > acc ? n : acc;
      },
      Kokkos::Max<double>(m));
  return m;
}

}  // namespace amphora::kernels::solid
