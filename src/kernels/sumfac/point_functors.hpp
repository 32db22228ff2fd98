#pragma once
// The physics of the matrix-free operators at one quadrature point, apart from the cell loop
// (CellOperatorKernel, GenericCellKernel), as deal.II's FEEvaluation user code or MFEM's
// partial-assembly point loops. A point functor P provides:
//
//   n_components                 components of the solution it acts on (blocked by component)
//   n_coefficients               numbers per point it needs: geometry, weight and fields folded in
//   n_fields                     components of a Q_k field read at the points (0: none)
//   reads_values, reads_gradients, writes_values, writes_gradients
//   structure                    a fast path the cell loop may take instead (PointStructure)
//   per_cell_geometry            coefficients(J, w, f) linear in w: one set per cell serves
//                                Cartesian and affine cells (times the weight at each point)
//   coefficients(J, w, f, c)     c[0 .. n_coefficients) from the Jacobian J_ab = dx_a/dxi_b,
//                                the weight w and the field values f (nullptr: no field)
//   at_point(c, u, g, u_out, g_out)
//                                u[comp], g[comp * dim + b] (reference gradient d/dxi_b) in,
//                                the integrands out: the operator is
//                                  (A u)_i = sum_q u_out . phi_i + g_out . grad_xi phi_i
//
// A functor that also needs the physical Laplacian of its first dim components (the viscous
// term of a strong residual) says so with laplacian_components = dim, gives J^-1 at the point
// through inverse_jacobian(c, b, a) = (J^-1)_ba, and takes at_point(c, u, g, lap, u_out, g_out).
//
// A functor that reads the physical gradient of some of its fields (a void fraction's) names
// them with gradient_field_first and n_gradient_fields and takes coefficients(J, w, f, fg, c),
// fg[e * dim + b] the reference gradient d/dxi_b of field gradient_field_first + e.
//
// All functions are templates on the number type (a SIMD batch of cells or double).
#include <type_traits>

#include <Kokkos_Core.hpp>

#include "kernels/kokkos_compat.hpp"
#include "kernels/sumfac/point_geometry.hpp"
#include "kernels/sumfac/simd.hpp"

namespace amphora::kernels::sumfac {

/// Components whose physical Laplacian functor P reads at the points (0: none).
template <class P, class = void>
struct laplacian_components : std::integral_constant<int, 0> {};
template <class P>
struct laplacian_components<P, std::void_t<decltype(P::laplacian_components)>>
    : std::integral_constant<int, P::laplacian_components> {};
template <class P>
inline constexpr int laplacian_components_v = laplacian_components<P>::value;

/// Fields whose gradients functor P reads at the points (0: none).
template <class P, class = void>
struct gradient_fields : std::integral_constant<int, 0> {};
template <class P>
struct gradient_fields<P, std::void_t<decltype(P::n_gradient_fields)>>
    : std::integral_constant<int, P::n_gradient_fields> {};
template <class P>
inline constexpr int gradient_fields_v = gradient_fields<P>::value;

/// Fast paths of the cell loop through the 1D matrices (Kronecker sums and products) or the
/// diagonal's 1D tensors: only for operators of this exact form.
enum class PointStructure { general, mass, laplace };

/// The coefficients of one point: c[e] at p[e * stride] (stride 1 per cell, n_points stored).
template <class T>
struct PointCoefficients {
  const T* p;
  long stride;
  KOKKOS_FORCEINLINE_FUNCTION const T& operator[](int e) const { return p[e * stride]; }
};

/// Mass: u_out = w det J u.
template <int dim>
struct MassPoint {
  static constexpr int n_components = 1, n_coefficients = 1, n_fields = 0;
  static constexpr bool reads_values = true, reads_gradients = false;
  static constexpr bool writes_values = true, writes_gradients = false;
  static constexpr PointStructure structure = PointStructure::mass;
  static constexpr bool per_cell_geometry = true;
  template <class T>
  KOKKOS_INLINE_FUNCTION void coefficients(const T* J, const T& w, const T*, T* c) const {
    c[0] = w * determinant<dim>(J);
  }
  template <class T, class C>
  KOKKOS_FORCEINLINE_FUNCTION void at_point(const C& c, const T* u, const T*, T* u_out, T*) const {
    u_out[0] = u[0] * c[0];
  }
};

/// Laplace with an optional coefficient a(x) (a field of one component):
/// g_out = G g, G = a w det J J^-1 J^-T (packed symmetric).
template <int dim>
struct LaplacePoint {
  static constexpr int n_components = 1, n_coefficients = n_symmetric<dim>, n_fields = 1;
  static constexpr bool reads_values = false, reads_gradients = true;
  static constexpr bool writes_values = false, writes_gradients = true;
  static constexpr PointStructure structure = PointStructure::laplace;
  static constexpr bool per_cell_geometry = true;
  template <class T>
  KOKKOS_INLINE_FUNCTION void coefficients(const T* J, const T& w, const T* f, T* c) const {
    const T scale = f ? w * f[0] : w;
    laplace_metric<dim>(J, scale, c);
  }
  template <class T, class C>
  KOKKOS_FORCEINLINE_FUNCTION void at_point(const C& c, const T*, const T* g, T*, T* g_out) const {
    for (int a = 0; a < dim; ++a) {
      T s = T(0.0);
      for (int e = 0; e < dim; ++e) s += c[sym_index<dim>(a, e)] * g[e];
      g_out[a] = s;
    }
  }
};

/// Convection by a velocity field b(x) (dim components): u_out = c . g, c = w det J J^-1 b.
template <int dim>
struct ConvectionPoint {
  static constexpr int n_components = 1, n_coefficients = dim, n_fields = dim;
  static constexpr bool reads_values = false, reads_gradients = true;
  static constexpr bool writes_values = true, writes_gradients = false;
  static constexpr PointStructure structure = PointStructure::general;
  static constexpr bool per_cell_geometry = true;
  template <class T>
  KOKKOS_INLINE_FUNCTION void coefficients(const T* J, const T& w, const T* f, T* c) const {
    T zero[dim];
    for (int a = 0; a < dim; ++a) zero[a] = T(0.0);
    convection_metric<dim>(J, w, f ? f : zero, c);
  }
  template <class T, class C>
  KOKKOS_FORCEINLINE_FUNCTION void at_point(const C& c, const T*, const T* g, T* u_out, T*) const {
    T s = T(0.0);
    for (int a = 0; a < dim; ++a) s += c[a] * g[a];
    u_out[0] = s;
  }
};

/// Isotropic linear elasticity, the bilinear form of sigma(u) : eps(v) with
/// sigma = lambda tr(eps) I + 2 mu eps, eps = (grad u + grad u^T) / 2: dim coupled components.
/// Coefficients: w det J, then J^-1 (row-major). J^-1 does not scale with the weight, so one
/// set per cell does not serve (per_cell_geometry false).
template <int dim>
struct ElasticityPoint {
  static constexpr int n_components = dim, n_coefficients = 1 + dim * dim, n_fields = 0;
  static constexpr bool reads_values = false, reads_gradients = true;
  static constexpr bool writes_values = false, writes_gradients = true;
  static constexpr PointStructure structure = PointStructure::general;
  static constexpr bool per_cell_geometry = false;
  double lambda = 1.0, mu = 1.0;

  template <class T>
  KOKKOS_INLINE_FUNCTION void coefficients(const T* J, const T& w, const T*, T* c) const {
    c[0] = w * inverse<dim>(J, c + 1);
  }
  template <class T, class C>
  KOKKOS_INLINE_FUNCTION void at_point(const C& c, const T*, const T* g, T*, T* g_out) const {
    T grad[dim * dim];  // du_i/dx_a = sum_b du_i/dxi_b dxi_b/dx_a
    for (int i = 0; i < dim; ++i)
      for (int a = 0; a < dim; ++a) {
        T s = T(0.0);
        for (int b = 0; b < dim; ++b) s += g[i * dim + b] * c[1 + b * dim + a];
        grad[i * dim + a] = s;
      }
    T trace = T(0.0);
    for (int a = 0; a < dim; ++a) trace += grad[a * dim + a];
    T sigma[dim * dim];
    for (int i = 0; i < dim; ++i)
      for (int a = 0; a < dim; ++a)
        sigma[i * dim + a] =
            T(mu) * (grad[i * dim + a] + grad[a * dim + i]) + (i == a ? T(lambda) * trace : T(0.0));
    for (int i = 0; i < dim; ++i)  // times w det J, back to reference: sigma J^-T
      for (int b = 0; b < dim; ++b) {
        T s = T(0.0);
        for (int a = 0; a < dim; ++a) s += sigma[i * dim + a] * c[1 + b * dim + a];
        g_out[i * dim + b] = c[0] * s;
      }
  }
};

namespace detail {

/// The SUPG/PSPG parameter from s = tau^-2, lane by lane (0 where s is not positive: the padding
/// lanes of a batch).
KOKKOS_INLINE_FUNCTION double tau_from(double s) { return s > 0.0 ? 1.0 / math::sqrt(s) : 0.0; }
template <int W>
KOKKOS_INLINE_FUNCTION Simd<W> tau_from(Simd<W> s) {
  for (int l = 0; l < W; ++l) s[l] = tau_from(s[l]);
  return s;
}
/// (|det J|^(1/dim) / k)^2, the squared length of a cell per degree (1 where det J is 0).
template <int dim>
KOKKOS_INLINE_FUNCTION double h_squared(double det, int k) {
  const double v = math::fabs(det);
  return v > 0.0 ? math::pow(v, 2.0 / dim) / (k * k) : 1.0;
}
template <int dim, int W>
KOKKOS_INLINE_FUNCTION Simd<W> h_squared(Simd<W> det, int k) {
  for (int l = 0; l < W; ++l) det[l] = h_squared<dim>(det[l], k);
  return det;
}

}  // namespace detail

/// The Oseen operator of one implicit step of incompressible flow with equal-order velocity and
/// pressure, stabilised by SUPG/PSPG and grad-div (Tezduyar, Adv. Appl. Mech. 28, 1992; the form
/// Lethe's matrix-free solver takes, Blais et al., J. Comput. Phys. 2020): dim + 1 coupled
/// components (u, p) and an advecting velocity b, a field of dim components. For test
/// functions (v, q):
///   (v, alpha u + b.grad u) + nu (grad v, grad u) - (div v, p) + (q, div u)
///     + gamma (div v, div u) + tau (b.grad v + grad q, alpha u + b.grad u + grad p),
/// tau = ((2 / dt)^2 + (2 |b| / h)^2 + 9 (4 nu / h^2)^2)^(-1/2), h = |det J|^(1/dim) / k at the
/// point (the viscous part of the strong residual is left out, as is usual for the Jacobian).
/// alpha is the BDF coefficient over dt; dt_inverse enters tau only (0: steady).
/// With `history` set, only the terms that multiply alpha u (alpha = 1): the right-hand side
/// of the BDF step from the history or a force, (v + tau b.grad v, h) + tau (grad q, h).
/// Coefficients: w det J, J^-1 (row-major), b, tau.
template <int dim>
struct OseenPoint {
  static constexpr int n_components = dim + 1, n_fields = dim;
  static constexpr int n_coefficients = 1 + dim * dim + dim + 1;
  static constexpr int laplacian_components = dim;
  static constexpr bool reads_values = true, reads_gradients = true;
  static constexpr bool writes_values = true, writes_gradients = true;
  static constexpr PointStructure structure = PointStructure::general;
  static constexpr bool per_cell_geometry = false;
  double nu = 1.0, alpha = 0.0, gamma = 0.0, dt_inverse = 0.0;
  int degree = 1;
  bool history = false;
  /// The strong residual includes -nu lap u (consistent at every degree; without it the
  /// stabilisation perturbs the solution by O(h^2) where viscosity dominates the cell).
  bool viscous_residual = true;

  KOKKOS_INLINE_FUNCTION bool needs_laplacian() const { return viscous_residual && !history; }
  template <class C>
  KOKKOS_INLINE_FUNCTION static auto inverse_jacobian(const C& c, int b, int a) {
    return c[1 + b * dim + a];
  }

  template <class T>
  KOKKOS_INLINE_FUNCTION void coefficients(const T* J, const T& w, const T* f, T* c) const {
    const T det = inverse<dim>(J, c + 1);
    c[0] = w * det;
    T bb = T(0.0);
    for (int a = 0; a < dim; ++a) {
      c[1 + dim * dim + a] = f ? f[a] : T(0.0);
      bb += c[1 + dim * dim + a] * c[1 + dim * dim + a];
    }
    const T h2 = detail::h_squared<dim>(det, degree);
    const T viscous = T(12.0 * nu) / h2;  // 3 * 4 nu / h^2, squared below: 9 (4 nu / h^2)^2
    c[1 + dim * dim + dim] =
        detail::tau_from(T(4.0 * dt_inverse * dt_inverse) + T(4.0) * bb / h2 + viscous * viscous);
  }

  template <class T, class C>
  KOKKOS_INLINE_FUNCTION void at_point(const C& c, const T* u, const T* g, const T* lap, T* u_out,
                                       T* g_out) const {
    T grad[(dim + 1) * dim];  // physical gradients of u_0 .. u_dim-1, p
    for (int i = 0; i <= dim; ++i)
      for (int a = 0; a < dim; ++a) {
        T s = T(0.0);
        for (int b = 0; b < dim; ++b) s += g[i * dim + b] * c[1 + b * dim + a];
        grad[i * dim + a] = s;
      }
    const T tau = c[1 + dim * dim + dim];
    T conv[dim], r[dim], div = T(0.0);
    for (int i = 0; i < dim; ++i) {
      T s = T(0.0);
      for (int a = 0; a < dim; ++a) s += c[1 + dim * dim + a] * grad[i * dim + a];
      conv[i] = s;
      div += grad[i * dim + i];
    }
    const T a_u = T(history ? 1.0 : alpha);
    for (int i = 0; i < dim; ++i) {
      r[i] = history ? u[i] : a_u * u[i] + conv[i] + grad[dim * dim + i];
      if (needs_laplacian()) r[i] -= T(nu) * lap[i];
    }
    T flux[(dim + 1) * dim];  // physical gradient integrands, then mapped back below
    for (int i = 0; i < dim; ++i) {
      u_out[i] = c[0] * (history ? u[i] : a_u * u[i] + conv[i]);
      for (int a = 0; a < dim; ++a) {
        T s = tau * c[1 + dim * dim + a] * r[i];
        if (!history) {
          s += T(nu) * grad[i * dim + a];
          if (a == i) s += T(gamma) * div - u[dim];
        }
        flux[i * dim + a] = s;
      }
    }
    u_out[dim] = history ? T(0.0) : c[0] * div;
    for (int a = 0; a < dim; ++a) flux[dim * dim + a] = tau * r[a];
    for (int i = 0; i <= dim; ++i)  // times w det J, to the reference gradients: flux J^-T
      for (int b = 0; b < dim; ++b) {
        T s = T(0.0);
        for (int a = 0; a < dim; ++a) s += flux[i * dim + a] * c[1 + b * dim + a];
        g_out[i * dim + b] = c[0] * s;
      }
  }
};

}  // namespace amphora::kernels::sumfac
