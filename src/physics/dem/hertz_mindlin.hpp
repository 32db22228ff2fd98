#pragma once
// Point-wise Hertz–Mindlin contact force (the law of LIGGGHTS' `hertz tangential history`,
// Di Renzo & Di Maio 2004; damping as Tsuji et al. 1992 with the restitution-calibrated
// factor of contact_model.hpp), Coulomb limit, constant-torque rolling resistance (Ai et al.
// 2011, model A) and SJKR cohesion. Inline and device-safe: the loops that apply it live in
// dem_system.cpp and know nothing of the law.
#include "kernels/kokkos_compat.hpp"
#include "physics/dem/contact_model.hpp"

namespace amphora::physics::dem {

struct ContactForce {
  double force[3];    ///< on particle i (normal + tangential + cohesion); j takes minus this
  double moment[3];   ///< n x (tangential force on i): i's centre, and j's, at distance l from
                      ///< the contact point take the torque l * moment from it
  double rolling[3];  ///< rolling-resistance torque on i; j takes minus this
  double normal;      ///< normal force magnitude (>0 repulsive), for diagnostics
};

/// Force and torque on particle i from a contact with j (or a wall).
///   n: unit vector from i's centre towards the contact partner; delta > 0: overlap
///   v_rel: velocity of i's contact point relative to j's (translation and rotation)
///   w_rel: omega_i - omega_j (rolling)
///   shear: tangential displacement history of this contact, updated in place.
///   vn: v_rel . n, the approach speed (> 0: approaching), which callers may know sooner than
///   v_rel and n (the rotational part of v_rel is normal to n).
KOKKOS_FORCEINLINE_FUNCTION ContactForce hertz_mindlin_force(
    const PairCoefficients& c, double r_eff, double m_eff, const double n[3], double delta,
    double vn, const double v_rel[3], const double w_rel[3], double dt, double shear[3]) {
  ContactForce out;
  // Contact radius a = sqrt(R* delta); stiffnesses grow with a, damping with sqrt(m* a).
  const double a = kernels::math::sqrt(r_eff * delta);
  const double sqrt_ma = kernels::math::sqrt(m_eff * a);
  const double kn = c.kn * a;
  const double kt = c.kt * a;
  const double gamma_n = c.gamma_n * sqrt_ma;
  const double gamma_t = c.gamma_t * sqrt_ma;

  const double vt[3] = {v_rel[0] - vn * n[0], v_rel[1] - vn * n[1], v_rel[2] - vn * n[2]};
  // Damping may not turn the contact attractive (the calibration in contact_model.cpp assumes
  // the same clamp).
  const double fn_raw = kn * delta + gamma_n * vn;
  const double fn = fn_raw > 0 ? fn_raw : 0.0;

  // Keep the history in the current tangent plane (projection, as LAMMPS/LIGGGHTS do), then
  // add the tangential displacement of this step.
  const double s_dot_n = shear[0] * n[0] + shear[1] * n[1] + shear[2] * n[2];
  for (int d = 0; d < 3; ++d) shear[d] += vt[d] * dt - s_dot_n * n[d];

  double ft[3];
  for (int d = 0; d < 3; ++d) ft[d] = -kt * shear[d] - gamma_t * vt[d];
  const double ft2 = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2];
  const double ft_max = c.friction * fn;
  if (ft2 > ft_max * ft_max) {  // sliding: cap at Coulomb and keep the spring consistent with it
    const double scale = ft_max / kernels::math::sqrt(ft2);
    for (int d = 0; d < 3; ++d) {
      ft[d] *= scale;
      shear[d] = kt > 0 ? -(ft[d] + gamma_t * vt[d]) / kt : 0.0;
    }
  }

  // SJKR cohesion: attraction k_c * contact area, area from the overlap (pi R* delta).
  const double f_coh = c.cohesion * kernels::math::pi * r_eff * delta;
  for (int d = 0; d < 3; ++d) out.force[d] = -(fn - f_coh) * n[d] + ft[d];

  // The tangential force at the contact point, l n from i's centre, has the torque l n x ft
  // on i; j's centre lies at -l' n from the point and takes -ft: the torque l' n x ft as well.
  out.moment[0] = n[1] * ft[2] - n[2] * ft[1];
  out.moment[1] = n[2] * ft[0] - n[0] * ft[2];
  out.moment[2] = n[0] * ft[1] - n[1] * ft[0];
  // Rolling resistance: a constant torque mu_r R* |F_n| against the relative rotation.
  const double w2 = w_rel[0] * w_rel[0] + w_rel[1] * w_rel[1] + w_rel[2] * w_rel[2];
  for (int d = 0; d < 3; ++d) out.rolling[d] = 0.0;
  if (c.rolling_friction > 0 && w2 > 0) {
    const double m = c.rolling_friction * r_eff * fn / kernels::math::sqrt(w2);
    for (int d = 0; d < 3; ++d) out.rolling[d] = -m * w_rel[d];
  }
  out.normal = fn;
  return out;
}

/// The same with vn = v_rel . n formed here.
KOKKOS_FORCEINLINE_FUNCTION ContactForce hertz_mindlin_force(
    const PairCoefficients& c, double r_eff, double m_eff, const double n[3], double delta,
    const double v_rel[3], const double w_rel[3], double dt, double shear[3]) {
  const double vn = v_rel[0] * n[0] + v_rel[1] * n[1] + v_rel[2] * n[2];
  return hertz_mindlin_force(c, r_eff, m_eff, n, delta, vn, v_rel, w_rel, dt, shear);
}

/// scale times the elastic energy of a Hertz contact, (8/15) E* sqrt(R*) delta^{5/2} (the
/// integral of the normal force k_n sqrt(R* delta) delta over the overlap).
KOKKOS_FORCEINLINE_FUNCTION double hertz_energy(double scale, double e_star, double r_eff,
                                                double delta) {
  return scale * (8.0 / 15.0) * e_star * kernels::math::sqrt(r_eff) * delta * delta *
         kernels::math::sqrt(delta);
}

}  // namespace amphora::physics::dem
