#pragma once
#include <stdexcept>
#include <string>
#include <type_traits>

#include "kernels/sumfac/batch_dof_access.hpp"
#include "kernels/sumfac/row_touch.hpp"
#include "kernels/sumfac/shape_data.hpp"
#include "kernels/sumfac/tensor_product_evaluator.hpp"
#include "kernels/sumfac/cell_operator_kernel.hpp"
#include "kernels/sumfac/lattice_interpolation.hpp"
#include "solvers/matrix_free/degree_dispatch.hpp"
#include "solvers/matrix_free/transfer.hpp"

namespace amphora::solvers::matrix_free {

template <int dim, class ExecSpace>
struct MatrixFreeTransfer<dim, ExecSpace>::Impl {
  static constexpr int W = kernels::sumfac::simd_width_v<ExecSpace>;
  using T = kernels::sumfac::Simd<W>;
  kernels::sumfac::QkLattice<dim> coarse, fine;  // both on the coarse cells
  Kokkos::View<long*, typename ExecSpace::memory_space> coarse_constrained, fine_constrained;
  int components = 1, constrained_components = 1;

  static void zero_constrained(const ExecSpace& exec,
                               const Kokkos::View<long*, typename ExecSpace::memory_space>& c,
                               double* y) {
    Kokkos::parallel_for(
        "amphora::MatrixFreeTransfer::constraints",
        kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(c.extent(0))),
        KOKKOS_LAMBDA(int i) { y[c(i)] = 0.0; });
  }
  std::shared_ptr<void> shape;
  kernels::sumfac::LatticeInterpolation<dim, typename ExecSpace::memory_space> lattice;  // halved
  void (*prolongate)(const Impl&, const ExecSpace&, const Vector&, const Vector&) = nullptr;
  void (*restrict_to_coarse)(const Impl&, const ExecSpace&, const Vector&, const Vector&) = nullptr;

  template <int n_pc, int n_pf>
  struct Kernel {
    kernels::sumfac::BatchDofAccess<dim, n_pc, W> c;
    kernels::sumfac::BatchDofAccess<dim, n_pf, W> f;
    kernels::sumfac::ShapeData<n_pc, n_pf> shape;
    using Eval = kernels::sumfac::TensorProductEvaluator<dim, n_pc, n_pf>;

    template <bool atomic>
    KOKKOS_INLINE_FUNCTION void prolongate(const double* xc, double* xf, int b,
                                           bool constrained) const {
      T uc[Eval::n_dofs], uf[Eval::n_points], w[Eval::n_points], tmp[Eval::n_scratch];
      typename kernels::sumfac::BatchDofAccess<dim, n_pc, W>::BatchIndex ic;
      typename kernels::sumfac::BatchDofAccess<dim, n_pf, W>::BatchIndex jf;
      c.batch_index(b, ic);
      f.batch_index(b, jf);
      c.gather(xc, ic, uc, constrained);
      Eval::values(shape, uc, uf, tmp);
      f.inverse_multiplicity(b, w);
      for (int i = 0; i < Eval::n_points; ++i) uf[i] *= w[i];
      f.template scatter_add<atomic>(xf, jf, uf, constrained);
    }
    template <bool atomic>
    KOKKOS_INLINE_FUNCTION void restrict_to_coarse(const double* xf, double* xc, int b,
                                                   bool constrained) const {
      T uc[Eval::n_dofs], uf[Eval::n_points], w[Eval::n_points], tmp[Eval::n_scratch];
      typename kernels::sumfac::BatchDofAccess<dim, n_pc, W>::BatchIndex ic;
      typename kernels::sumfac::BatchDofAccess<dim, n_pf, W>::BatchIndex jf;
      c.batch_index(b, ic);
      f.batch_index(b, jf);
      f.gather(xf, jf, uf, constrained);
      f.inverse_multiplicity(b, w);
      for (int i = 0; i < Eval::n_points; ++i) uf[i] *= w[i];
      Eval::integrate_values(shape, uf, uc, tmp);
      c.template scatter_add<atomic>(xc, ic, uc, constrained);
    }
  };

  template <int n_pc, int n_pf>
  static Kernel<n_pc, n_pf> kernel(const Impl& impl) {
    Kernel<n_pc, n_pf> k;
    k.c.lattice = impl.coarse;
    k.f.lattice = impl.fine;
    k.shape = *static_cast<const kernels::sumfac::ShapeData<n_pc, n_pf>*>(impl.shape.get());
    return k;
  }

  template <int n_pc, int n_pf>
  static void prolongate_impl(const Impl& impl, const ExecSpace& exec, const Vector& xc,
                              const Vector& xf) {
    const auto k = kernel<n_pc, n_pf>(impl);
    constexpr bool atomic = !kernels::runs_on_host_v<ExecSpace>;
    if (atomic) Kokkos::deep_copy(exec, xf, 0.0);
    const long nc = impl.coarse.n_dofs(), nf = impl.fine.n_dofs();
    for (int comp = 0; comp < impl.components; ++comp) {
      const double* src = xc.data() + comp * nc;
      double* dst = xf.data() + comp * nf;
      const bool cons = comp < impl.constrained_components;
      kernels::sumfac::for_each_batch_coloured(
          exec, impl.fine, "amphora::MatrixFreeTransfer::prolongate",
          kernels::sumfac::FirstTouchZero<dim>{impl.fine, dst, 1},
          KOKKOS_LAMBDA(int b) { k.template prolongate<atomic>(src, dst, b, cons); });
      if (cons) zero_constrained(exec, impl.fine_constrained, dst);
    }
  }

  template <int n_pc, int n_pf>
  static void restrict_impl(const Impl& impl, const ExecSpace& exec, const Vector& xf,
                            const Vector& xc) {
    const auto k = kernel<n_pc, n_pf>(impl);
    constexpr bool atomic = !kernels::runs_on_host_v<ExecSpace>;
    if (atomic) Kokkos::deep_copy(exec, xc, 0.0);
    const long nc = impl.coarse.n_dofs(), nf = impl.fine.n_dofs();
    for (int comp = 0; comp < impl.components; ++comp) {
      const double* src = xf.data() + comp * nf;
      double* dst = xc.data() + comp * nc;
      const bool cons = comp < impl.constrained_components;
      kernels::sumfac::for_each_batch_coloured(
          exec, impl.coarse, "amphora::MatrixFreeTransfer::restrict",
          kernels::sumfac::FirstTouchZero<dim>{impl.coarse, dst, 1},
          KOKKOS_LAMBDA(int b) { k.template restrict_to_coarse<atomic>(src, dst, b, cons); });
      if (cons) zero_constrained(exec, impl.coarse_constrained, dst);
    }
  }
  static void lattice_prolongate(const Impl& impl, const ExecSpace& exec, const Vector& xc,
                                 const Vector& xf) {
    const long nc = impl.coarse.n_dofs(), nf = impl.fine.n_dofs();
    for (int comp = 0; comp < impl.components; ++comp)
      impl.lattice.prolongate(exec, xc.data() + comp * nc, xf.data() + comp * nf,
                              comp < impl.constrained_components);
  }
  static void lattice_restrict(const Impl& impl, const ExecSpace& exec, const Vector& xf,
                               const Vector& xc) {
    const long nc = impl.coarse.n_dofs(), nf = impl.fine.n_dofs();
    for (int comp = 0; comp < impl.components; ++comp)
      impl.lattice.restrict_to_coarse(exec, xf.data() + comp * nf, xc.data() + comp * nc,
                                      comp < impl.constrained_components);
  }
};

namespace detail {
/// Compiled (k_c, k_f) pairs: k_f in k_c + 1 .. 2 k_c + 1 (every step of degree bisection) up to
/// the compiled degree.
template <int kc = 1, class F>
void dispatch_transfer(int coarse_degree, int fine_degree, F&& f) {
  if (coarse_degree == kc) {
    if constexpr (kc + 1 <= max_compiled_degree)
      if (fine_degree == kc + 1)
        return f(std::integral_constant<int, kc + 1>{}, std::integral_constant<int, kc + 2>{});
    if constexpr (2 * kc <= max_compiled_degree)
      if (fine_degree == 2 * kc)
        return f(std::integral_constant<int, kc + 1>{}, std::integral_constant<int, 2 * kc + 1>{});
    if constexpr (2 * kc + 1 <= max_compiled_degree)
      if (fine_degree == 2 * kc + 1)
        return f(std::integral_constant<int, kc + 1>{}, std::integral_constant<int, 2 * kc + 2>{});
  }
  if constexpr (kc + 1 < max_compiled_degree) {
    return dispatch_transfer<kc + 1>(coarse_degree, fine_degree, f);
  } else {
    throw std::invalid_argument(
        "MatrixFreeTransfer: no kernel from degree " + std::to_string(coarse_degree) + " to " +
        std::to_string(fine_degree) + "; compiled: k_c + 1, 2 k_c, 2 k_c + 1 up to degree " +
        std::to_string(max_compiled_degree));
  }
}
}  // namespace detail

template <int dim, class ExecSpace>
MatrixFreeTransfer<dim, ExecSpace>::MatrixFreeTransfer(const Space& coarse, const Space& fine,
                                                       int components, int constrained_components) {
  auto impl = std::make_shared<Impl>();
  impl->components = components;
  impl->constrained_components = constrained_components < 0 ? components : constrained_components;
  impl->coarse = coarse.lattice();
  impl->coarse_constrained = coarse.constrained_dofs();
  impl->fine_constrained = fine.constrained_dofs();
  const auto& mc = coarse.mesh();
  const auto& mf = fine.mesh();
  bool same = true, refined = true, halved = true;
  for (int d = 0; d < dim; ++d) {
    same = same && mf.cells[d] == mc.cells[d];
    refined = refined && mf.cells[d] == 2 * mc.cells[d];
    halved = halved && mc.cells[d] == (mf.cells[d] + 1) / 2;
  }
  int fine_degree = fine.degree();
  if (same && fine.degree() > coarse.degree()) {
    impl->fine = fine.lattice();
  } else if (refined && fine.degree() == 1 && coarse.degree() == 1) {
    bool periodic[3] = {false, false, false};
    for (int d = 0; d < dim; ++d) periodic[d] = mc.periodic(d);
    impl->fine = kernels::sumfac::QkLattice<dim>::create(2, mc.cells.data(), periodic,
                                                         mc.dirichlet_faces(), impl->coarse.width);
    impl->fine.shared_faces = impl->coarse.shared_faces;
    fine_degree = 2;
  } else if (halved && fine.degree() == 1 && coarse.degree() == 1) {
    impl->fine = fine.lattice();
    impl->lattice = {coarse.lattice(), fine.lattice()};
    impl->prolongate = &Impl::lattice_prolongate;
    impl->restrict_to_coarse = &Impl::lattice_restrict;
    impl_ = impl;
    return;
  } else {
    throw std::invalid_argument(
        "MatrixFreeTransfer: the fine space must have the coarse cells and a higher degree, or "
        "twice the cells per direction, or n cells where the coarse has ceil(n / 2), with both "
        "of degree 1");
  }
  detail::dispatch_transfer(coarse.degree(), fine_degree, [&](auto pc, auto pf) {
    constexpr int n_pc = decltype(pc)::value, n_pf = decltype(pf)::value;
    impl->shape = std::make_shared<kernels::sumfac::ShapeData<n_pc, n_pf>>(
        kernels::sumfac::ShapeData<n_pc, n_pf>::interpolation());
    impl->prolongate = &Impl::template prolongate_impl<n_pc, n_pf>;
    impl->restrict_to_coarse = &Impl::template restrict_impl<n_pc, n_pf>;
  });
  impl_ = impl;
}

template <int dim, class ExecSpace>
void MatrixFreeTransfer<dim, ExecSpace>::prolongate(const ExecSpace& exec, const Vector& coarse,
                                                    const Vector& fine) const {
  impl_->prolongate(*impl_, exec, coarse, fine);
}

template <int dim, class ExecSpace>
void MatrixFreeTransfer<dim, ExecSpace>::restrict_to_coarse(const ExecSpace& exec,
                                                            const Vector& fine,
                                                            const Vector& coarse) const {
  impl_->restrict_to_coarse(*impl_, exec, fine, coarse);
}

}  // namespace amphora::solvers::matrix_free
