#pragma once
// Particle migration in the manner of Cabana's Distributor: each owned particle goes to the
// rank dest(i) names (-1: removed). Records are packed and unpacked on the device; only the
// plan (who goes where, from dest) and the MPI messages pass through the host.
#include <vector>

#include "mesh/particles/particle_fields.hpp"
#include "mesh/particles/spatial_decomposition.hpp"

namespace amphora::mesh::particles {

template <class ExecSpace>
class ParticleMigration {
 public:
  using Mem = typename ExecSpace::memory_space;

  /// The plan for particles 0 .. n with destinations dest (ranks, or -1).
  ParticleMigration(const SpatialDecomposition& dec, const Kokkos::View<int*, Mem>& dest, int n)
      : dec_(dec) {
    const int me = dec.comm().rank(), p = dec.comm().size();
    auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(),
                                                 Kokkos::subview(dest, Kokkos::make_pair(0, n)));
    // staying ones first, then to rank 0, 1, ... (index order within): a counting sort
    counts_.assign(p, 0);
    for (int i = 0; i < n; ++i)
      if (h(i) >= 0) ++counts_[h(i)];
    staying_ = counts_[me];
    counts_[me] = 0;
    std::vector<int> at(p, 0);
    for (int r = 0, sum = staying_; r < p; ++r) at[r] = sum, sum += counts_[r];
    std::vector<int> order(size_t(at[p - 1] + counts_[p - 1]));
    for (int i = 0, kept = 0; i < n; ++i)
      if (h(i) == me)
        order[kept++] = i;
      else if (h(i) >= 0)
        order[at[h(i)]++] = i;
    order_ = Kokkos::View<int*, Mem>("amphora::particles::migration_order", order.size());
    auto ho = Kokkos::create_mirror_view(order_);
    for (size_t k = 0; k < order.size(); ++k) ho(k) = order[k];
    Kokkos::deep_copy(order_, ho);
  }

  /// Packs the particles that stay and those that leave (from the arrays `from`), exchanges
  /// the latter, and returns how many particles this rank will hold. Collective.
  int send(const ExecSpace& exec, const ParticleFields<ExecSpace>& from) {
    const int w = from.width(), moving = static_cast<int>(order_.extent(0));
    Kokkos::View<double*, Mem> buf("amphora::particles::migration_buffer", size_t(moving) * w);
    from.pack(exec, order_, moving, buf);
    exec.fence();
    auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), buf);
    std::vector<std::vector<double>> out(counts_.size());
    size_t at = size_t(staying_) * w;
    for (size_t r = 0; r < counts_.size(); ++r) {
      out[r].assign(h.data() + at, h.data() + at + size_t(counts_[r]) * w);
      at += size_t(counts_[r]) * w;
    }
    const std::vector<double> in = dec_.exchange_all(out);
    const int arriving = static_cast<int>(in.size()) / w;
    records_ = Kokkos::View<double*, Mem>("amphora::particles::migration_records",
                                          size_t(staying_ + arriving) * w);
    auto hr = Kokkos::create_mirror_view(records_);
    std::copy(h.data(), h.data() + size_t(staying_) * w, hr.data());
    std::copy(in.begin(), in.end(), hr.data() + size_t(staying_) * w);
    Kokkos::deep_copy(records_, hr);
    return staying_ + arriving;
  }
  /// Unpacks what send() gathered into particles 0 .. send()'s count of the arrays `to` (the
  /// same fields, grown to hold them): those that stayed, in their order, then the arrivals in
  /// rank order.
  void receive(const ExecSpace& exec, const ParticleFields<ExecSpace>& to) const {
    to.unpack(exec, records_, static_cast<int>(records_.extent(0)) / to.width(), 0);
    exec.fence();
  }

 private:
  const SpatialDecomposition& dec_;
  std::vector<int> counts_;
  int staying_ = 0;
  Kokkos::View<int*, Mem> order_;
  Kokkos::View<double*, Mem> records_;
};

}  // namespace amphora::mesh::particles
