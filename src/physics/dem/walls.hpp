#pragma once
// Walls as rigid analytic surfaces: planes and (finite) cylinders, each with a rigid motion
// (translation velocity, and angular velocity about a centre) so a plane can move and a
// cylinder can turn as a drum. The contact geometry is point-wise and device-safe.
#include "kernels/kokkos_compat.hpp"

namespace amphora::physics::dem {

enum WallType : int { kPlane = 0, kCylinder = 1 };

struct Wall {
  int type = kPlane;
  double point[3] = {0, 0, 0};     ///< plane: a point on it at t = 0; cylinder: axis start at t = 0
  double axis[3] = {0, 0, 1};      ///< plane: unit normal into the domain; cylinder: unit axis
  double radius = 0;               ///< cylinder radius (particles inside)
  double length = 0;               ///< cylinder length along the axis from `point` (0: infinite)
  double velocity[3] = {0, 0, 0};  ///< translation
  double angular_velocity[3] = {0, 0, 0};  ///< rotation about `point` (+ velocity t)
  int material = 0;
};

/// Contact of a sphere (centre x, radius r) with wall w at time t. Returns false if none;
/// otherwise n (unit, from the centre towards the wall), overlap delta > 0 and the wall's
/// velocity at the contact point.
KOKKOS_INLINE_FUNCTION bool wall_contact(const Wall& w, double t, const double x[3], double r,
                                         double n[3], double& delta, double v_wall[3]) {
  double p[3];
  for (int d = 0; d < 3; ++d) p[d] = w.point[d] + w.velocity[d] * t;
  const double rel[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]};
  const double along = rel[0] * w.axis[0] + rel[1] * w.axis[1] + rel[2] * w.axis[2];
  double c[3];  // contact point
  if (w.type == kPlane) {
    delta = r - along;  // along: signed distance of the centre from the plane
    if (delta <= 0) return false;
    for (int d = 0; d < 3; ++d) {
      n[d] = -w.axis[d];
      c[d] = x[d] - along * w.axis[d];
    }
  } else {
    if (w.length > 0 && (along < 0 || along > w.length)) return false;
    double radial[3];
    for (int d = 0; d < 3; ++d) radial[d] = rel[d] - along * w.axis[d];
    const double rho =
        kernels::math::sqrt(radial[0] * radial[0] + radial[1] * radial[1] + radial[2] * radial[2]);
    delta = rho + r - w.radius;
    if (delta <= 0 || rho == 0) return false;
    for (int d = 0; d < 3; ++d) {
      n[d] = radial[d] / rho;
      c[d] = p[d] + along * w.axis[d] + w.radius * n[d];
    }
  }
  const double a[3] = {c[0] - p[0], c[1] - p[1], c[2] - p[2]};
  const double* om = w.angular_velocity;
  v_wall[0] = w.velocity[0] + om[1] * a[2] - om[2] * a[1];
  v_wall[1] = w.velocity[1] + om[2] * a[0] - om[0] * a[2];
  v_wall[2] = w.velocity[2] + om[0] * a[1] - om[1] * a[0];
  return true;
}

/// True if the centre of a sphere lies on the wall's outer side (outside the domain it bounds).
KOKKOS_INLINE_FUNCTION bool outside_wall(const Wall& w, double t, const double x[3]) {
  double rel[3];
  for (int d = 0; d < 3; ++d) rel[d] = x[d] - (w.point[d] + w.velocity[d] * t);
  const double along = rel[0] * w.axis[0] + rel[1] * w.axis[1] + rel[2] * w.axis[2];
  if (w.type == kPlane) return along < 0;
  if (w.length > 0 && (along < 0 || along > w.length)) return false;
  double r2 = 0;
  for (int d = 0; d < 3; ++d) {
    const double q = rel[d] - along * w.axis[d];
    r2 += q * q;
  }
  return r2 > w.radius * w.radius;
}

}  // namespace amphora::physics::dem
