#pragma once
// The point functor of one implicit step of the volume-averaged Navier-Stokes equations (VANS)
// of unresolved CFD-DEM, beside OseenPoint so that plain flow pays nothing for it.
#include <Kokkos_Core.hpp>

#include "kernels/sumfac/point_functors.hpp"

namespace amphora::kernels::sumfac {

/// The stabilised Oseen operator of VANS with a given void fraction eps(x) (Zhou, Kuang, Chu &
/// Yu, J. Fluid Mech. 661 (2010) 482, models A and B; the SUPG/PSPG and grad-div form of
/// Lethe's VANS solver, Geitani, Golshan & Blais, 2023). Fields (blocked): the advecting
/// velocity b (dim), eps, and the implicit particle drag beta (per unit mass and volume: the
/// exchange force's u part, beta u). For test functions (v, q), model A:
///   (v, eps (alpha u + b.grad u) + beta u) + nu (grad v, eps grad u)
///     - (eps div v + v.grad eps, p) + (q, eps div u + u.grad eps)
///     + gamma (div v, eps div u + u.grad eps) + tau (b.grad v + grad q, r),
///   r = eps (alpha u + b.grad u + grad p) + beta u - nu (eps lap u + grad eps.grad u),
/// the pressure term being (v, eps grad p) integrated by parts (eps = 1 gives OseenPoint
/// exactly, and the do-nothing outflow keeps its meaning). Model B: (div v, p) and grad p in r
/// without eps. With `history` set, only the terms of alpha u (alpha = 1):
/// the right-hand side (v + tau b.grad v, eps h) + tau (grad q, eps h) + (q, h_p)
/// + gamma (div v, h_p), h_p the continuity's source -d eps / dt (grad-div stays consistent
/// where the void fraction changes in time). tau as OseenPoint's with the drag's rate beta / eps
/// added as a reaction's ((beta / eps)^2 in tau^-2): a dense bed's drag would otherwise make
/// tau beta large and the stabilisation dominate (docs/cfd_dem.md). With `load_only` as well,
/// only the stabilisation's share of a load density f (the particles' forces, whose Galerkin
/// part (v, f) is given integrated): tau (b.grad v + grad q, f), so that r's balance holds.
/// Coefficients: w det J, J^-1 (row-major), b, eps, grad eps, beta, tau.
template <int dim>
struct VansPoint {
  static constexpr int n_components = dim + 1, n_fields = dim + 2;
  /// The field whose physical gradient the operator reads (eps), one of them.
  static constexpr int gradient_field_first = dim, n_gradient_fields = 1;
  static constexpr int B = 1 + dim * dim, E = B + dim, G = E + 1, K = G + dim, TAU = K + 1;
  static constexpr int n_coefficients = TAU + 1;
  static constexpr int laplacian_components = dim;
  static constexpr bool reads_values = true, reads_gradients = true;
  static constexpr bool writes_values = true, writes_gradients = true;
  static constexpr PointStructure structure = PointStructure::general;
  static constexpr bool per_cell_geometry = false;
  double nu = 1.0, alpha = 0.0, gamma = 0.0, dt_inverse = 0.0;
  int degree = 1;
  bool history = false;
  bool viscous_residual = true;
  bool model_b = false;
  bool load_only = false;

  KOKKOS_INLINE_FUNCTION bool needs_laplacian() const { return viscous_residual && !history; }
  template <class C>
  KOKKOS_INLINE_FUNCTION static auto inverse_jacobian(const C& c, int b, int a) {
    return c[1 + b * dim + a];
  }

  /// fg: eps's reference gradient at the point.
  template <class T>
  KOKKOS_INLINE_FUNCTION void coefficients(const T* J, const T& w, const T* f, const T* fg,
                                           T* c) const {
    const T det = inverse<dim>(J, c + 1);
    c[0] = w * det;
    T bb = T(0.0);
    for (int a = 0; a < dim; ++a) {
      c[B + a] = f[a];
      bb += f[a] * f[a];
      T s = T(0.0);
      for (int b = 0; b < dim; ++b) s += fg[b] * c[1 + b * dim + a];
      c[G + a] = s;
    }
    c[E] = f[dim], c[K] = f[dim + 1];
    const T h2 = detail::h_squared<dim>(det, degree);
    const T viscous = T(12.0 * nu) / h2;
    const T reaction = f[dim + 1] / f[dim];  // the drag's rate beta / eps, as a reaction's
    c[TAU] = detail::tau_from(T(4.0 * dt_inverse * dt_inverse) + T(4.0) * bb / h2 +
                              viscous * viscous + reaction * reaction);
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
    const T eps = c[E], tau = c[TAU];
    T flux[(dim + 1) * dim];  // physical gradient integrands, mapped back below
    if (history) {
      const T w = load_only ? T(1.0) : eps;  // a load density f enters as f, h as eps h
      for (int i = 0; i < dim; ++i) {
        u_out[i] = load_only ? T(0.0) : c[0] * eps * u[i];
        for (int a = 0; a < dim; ++a) flux[i * dim + a] = tau * c[B + a] * w * u[i];
        // grad-div of div(eps u) = -d eps / dt
        if (!load_only) flux[i * dim + i] += T(gamma) * u[dim];
        flux[dim * dim + i] = tau * w * u[i];
      }
      u_out[dim] = load_only ? T(0.0) : c[0] * u[dim];
    } else {
      residual_terms(c, u, grad, lap, u_out, flux);
    }
    for (int i = 0; i <= dim; ++i)  // times w det J, to the reference gradients: flux J^-T
      for (int b = 0; b < dim; ++b) {
        T s = T(0.0);
        for (int a = 0; a < dim; ++a) s += flux[i * dim + a] * c[1 + b * dim + a];
        g_out[i * dim + b] = c[0] * s;
      }
  }

  /// The operator's integrands (not history): values into u_out (times w det J), physical
  /// gradient integrands into flux.
  template <class T, class C>
  KOKKOS_INLINE_FUNCTION void residual_terms(const C& c, const T* u, const T* grad, const T* lap,
                                             T* u_out, T* flux) const {
    const T eps = c[E], beta = c[K], tau = c[TAU], p = u[dim];
    T div = T(0.0), u_geps = T(0.0);
    for (int i = 0; i < dim; ++i) div += grad[i * dim + i], u_geps += u[i] * c[G + i];
    const T div_eps_u = eps * div + u_geps;
    const T p_scale = model_b ? T(1.0) : eps;  // eps grad p (A) or grad p (B)
    T r[dim];
    for (int i = 0; i < dim; ++i) {
      T conv = T(0.0), geps_grad = T(0.0);
      for (int a = 0; a < dim; ++a) {
        conv += c[B + a] * grad[i * dim + a];
        geps_grad += c[G + a] * grad[i * dim + a];
      }
      const T inertia = eps * (T(alpha) * u[i] + conv) + beta * u[i];
      r[i] = inertia + p_scale * grad[dim * dim + i];
      if (needs_laplacian()) r[i] -= T(nu) * (eps * lap[i] + geps_grad);
      u_out[i] = c[0] * (inertia - (model_b ? T(0.0) : c[G + i] * p));
      for (int a = 0; a < dim; ++a) {
        T s = tau * c[B + a] * r[i] + T(nu) * eps * grad[i * dim + a];
        if (a == i) s += T(gamma) * div_eps_u - p_scale * p;
        flux[i * dim + a] = s;
      }
    }
    u_out[dim] = c[0] * div_eps_u;
    for (int a = 0; a < dim; ++a) flux[dim * dim + a] = tau * r[a];
  }
};

}  // namespace amphora::kernels::sumfac
