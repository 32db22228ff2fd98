#pragma once
// Particle migration in the manner of Cabana's Distributor: each owned particle goes to the
// rank dest(i) names (-1: removed). Records are packed and unpacked on the device. On one rank
// (removals only) the plan is a device scan and nothing passes through the host; on several,
// the plan (who goes where, from dest) and the MPI messages do.
#include <vector>

#include "kernels/grow_view.hpp"
#include "mesh/particles/particle_fields.hpp"
#include "mesh/particles/spatial_decomposition.hpp"

namespace amphora::mesh::particles {

/// The arrays a migration works in, kept by its owner from one migration to the next: they
/// are reallocated only when too small.
template <class Mem>
struct MigrationBuffers {
  Kokkos::View<int*, Mem> order;       ///< the particles packed: staying ones, then by rank
  Kokkos::View<double*, Mem> records;  ///< packed records, then those this rank will hold
};

template <class ExecSpace>
class ParticleMigration {
 public:
  using Mem = typename ExecSpace::memory_space;

  /// The plan for particles 0 .. n with destinations dest (ranks, or -1), in `buffers`.
  ParticleMigration(const ExecSpace& exec, const SpatialDecomposition& dec,
                    const Kokkos::View<int*, Mem>& dest, int n, MigrationBuffers<Mem>& buffers)
      : dec_(dec), buffers_(buffers) {
    kernels::grow_uninitialized(buffers_.order, n, "amphora::particles::migration_order");
    if (dec.comm().size() == 1)
      plan_on_device(exec, dest, n);
    else
      plan_on_host(dest, n);
  }

  /// Packs the particles that stay and those that leave (from the arrays `from`), exchanges
  /// the latter, and returns how many particles this rank will hold. Collective.
  int send(const ExecSpace& exec, const ParticleFields<ExecSpace>& from) {
    const int w = from.width();
    kernels::grow_uninitialized(buffers_.records, size_t(moving_) * w,
                                "amphora::particles::migration_records");
    from.pack(exec, buffers_.order, moving_, buffers_.records);
    exec.fence();
    if (dec_.comm().size() == 1) return held_ = staying_;  // the records are in place
    const auto packed =
        Kokkos::subview(buffers_.records, Kokkos::make_pair(size_t(0), size_t(moving_) * w));
    auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), packed);
    std::vector<std::vector<double>> out(counts_.size());
    size_t at = size_t(staying_) * w;
    for (size_t r = 0; r < counts_.size(); ++r) {
      out[r].assign(h.data() + at, h.data() + at + size_t(counts_[r]) * w);
      at += size_t(counts_[r]) * w;
    }
    const std::vector<double> in = dec_.exchange_all(out);
    held_ = staying_ + static_cast<int>(in.size()) / w;
    std::vector<double> held(h.data(), h.data() + size_t(staying_) * w);
    held.insert(held.end(), in.begin(), in.end());
    kernels::grow_uninitialized(buffers_.records, held.size(),
                                "amphora::particles::migration_records");
    Kokkos::deep_copy(Kokkos::subview(buffers_.records, Kokkos::make_pair(size_t(0), held.size())),
                      Kokkos::View<const double*, kernels::HostMemSpace, Kokkos::MemoryUnmanaged>(
                          held.data(), held.size()));
    return held_;
  }
  /// Unpacks what send() gathered into particles 0 .. send()'s count of the arrays `to` (the
  /// same fields, grown to hold them): those that stayed, in their order, then the arrivals in
  /// rank order.
  void receive(const ExecSpace& exec, const ParticleFields<ExecSpace>& to) const {
    to.unpack(exec, buffers_.records, held_, 0);
    exec.fence();
  }

 public:  // (CUDA: extended lambdas may not live in private member functions)
  /// One rank: the particles that stay, in index order (a scan), and none to send.
  void plan_on_device(const ExecSpace& exec, const Kokkos::View<int*, Mem>& dest, int n) {
    const auto order = buffers_.order;
    int kept = 0;
    Kokkos::parallel_scan(
        "amphora::particles::migration_plan", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i, int& partial, bool final) {
          const bool stays = dest(i) >= 0;
          if (final && stays) order(partial) = i;
          partial += stays ? 1 : 0;
        },
        kept);
    counts_.assign(1, 0);
    staying_ = moving_ = kept;
  }

 private:
  /// Several ranks: staying ones first, then to rank 0, 1, ... (index order within): a
  /// counting sort on the host.
  void plan_on_host(const Kokkos::View<int*, Mem>& dest, int n) {
    const int me = dec_.comm().rank(), p = dec_.comm().size();
    auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(),
                                                 Kokkos::subview(dest, Kokkos::make_pair(0, n)));
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
    moving_ = static_cast<int>(order.size());
    Kokkos::deep_copy(Kokkos::subview(buffers_.order, Kokkos::make_pair(0, moving_)),
                      Kokkos::View<const int*, kernels::HostMemSpace, Kokkos::MemoryUnmanaged>(
                          order.data(), order.size()));
  }

  const SpatialDecomposition& dec_;
  MigrationBuffers<Mem>& buffers_;
  std::vector<int> counts_;
  int staying_ = 0, moving_ = 0, held_ = 0;
};

}  // namespace amphora::mesh::particles
