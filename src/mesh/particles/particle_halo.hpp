#pragma once
// Ghost particles in the manner of Cabana's Halo: copies of the neighbouring ranks' particles
// within a width of this rank's subdomain, gathered face by face (x, then y, then z, each
// forwarding the ghosts of the directions before, so edges and corners arrive), and refreshed
// each step along the same plan. Records are chosen, packed and unpacked on the device; the
// MPI messages pass through host buffers (the buffers themselves on host spaces). Across a
// periodic direction spanned by this rank alone, the ghosts are its own particles' images,
// copied on the device.
#include <functional>
#include <vector>

#include "mesh/particles/particle_fields.hpp"
#include "mesh/particles/spatial_decomposition.hpp"

namespace amphora::mesh::particles {

template <class ExecSpace>
class ParticleHalo {
 public:
  using Mem = typename ExecSpace::memory_space;
  using Positions = Kokkos::View<double* [3], Kokkos::LayoutRight, Mem>;
  /// The owner's arrays grown to hold a number of particles: the ghost record and the
  /// positions ghosts are chosen by.
  struct Arrays {
    ParticleFields<ExecSpace> record;
    Positions where;
  };

  /// Gathers the ghosts of particles 0 .. n_owned (placed after them) and returns how many
  /// arrived. A particle becomes a ghost across face (d, side) if where(i, d) lies within
  /// `width` of it; across a periodic face its ghost is its image (the record's positions
  /// shifted by the box's length), on this rank itself where one block spans the direction.
  /// Collective.
  int build(const ExecSpace& exec, const SpatialDecomposition& dec, int n_owned, double width,
            const std::function<Arrays(int capacity)>& grow) {
    legs_.clear();
    if (!has_neighbours(dec)) return 0;
    const auto lo = dec.lo(dec.comm().rank()), hi = dec.hi(dec.comm().rank());
    int total = n_owned;
    Arrays a = grow(total);
    for (int d = 0; d < 3; ++d) {
      if (dec.neighbor(d, 0) < 0 && dec.neighbor(d, 1) < 0) continue;  // walls: no leg
      // never ghosts that came in along this direction (they would go back home)
      const int candidates = total;
      for (int side = 0; side < 2; ++side) {
        Leg leg{d, side, {}, total, 0, {}, {}, -1, dec.image_shift(d, side), self_leg(dec, d)};
        const double bound = side == 0 ? lo[d] + width : hi[d] - width;
        leg.send = dec.neighbor(d, side) >= 0 ? choose(exec, a.where, candidates, d, side, bound)
                                              : Kokkos::View<int*, Mem>("amphora::halo::send", 0);
        const int ns = static_cast<int>(leg.send.extent(0)), w = a.record.width();
        Kokkos::View<double*, Mem> buf("amphora::halo::records", size_t(ns) * w);
        a.record.pack(exec, leg.send, ns, buf);
        exec.fence();
        if (leg.self) {  // this rank's own images: no message, no host copy
          leg.recv_count = ns;
          a = grow(total + ns);
          a.record.unpack(exec, buf, ns, total, d, leg.shift);
        } else {
          auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), buf);
          const std::vector<double> in =
              dec.exchange_face(d, side, std::vector<double>(h.data(), h.data() + h.size()));
          leg.recv_count = static_cast<int>(in.size()) / w;
          a = grow(total + leg.recv_count);
          if (!in.empty()) {
            Kokkos::View<double*, Mem> rbuf("amphora::halo::arrived", in.size());
            auto hr = Kokkos::create_mirror_view(rbuf);
            std::copy(in.begin(), in.end(), hr.data());
            Kokkos::deep_copy(rbuf, hr);
            a.record.unpack(exec, rbuf, leg.recv_count, total, d, leg.shift);
          }
        }
        total += leg.recv_count;
        legs_.push_back(leg);
      }
    }
    exec.fence();
    return total - n_owned;
  }

  /// Copies `moving` (the fields that change between builds) of the particles the plan sends
  /// to the ghosts they became (images shifted as in build). Collective.
  void forward(const ExecSpace& exec, const SpatialDecomposition& dec,
               const ParticleFields<ExecSpace>& moving) {
    const int w = moving.width();
    for (auto& leg : legs_) {
      const int ns = static_cast<int>(leg.send.extent(0));
      if (leg.buffer_width != w) {  // kept from step to step
        leg.buffer_width = w;
        leg.send_buf = Kokkos::View<double*, Mem>("amphora::halo::send_buf", size_t(ns) * w);
        leg.recv_buf = leg.self ? leg.send_buf
                                : Kokkos::View<double*, Mem>("amphora::halo::recv_buf",
                                                             size_t(leg.recv_count) * w);
      }
      if (ns > 0) moving.pack(exec, leg.send, ns, leg.send_buf);
      if (!leg.self) {
        // host mirrors (the buffers themselves on host spaces): both sides know the sizes. An
        // empty buffer is not copied (Kokkos fences on every copy of an empty View).
        auto hb = Kokkos::create_mirror_view(leg.send_buf);
        const auto hrb = Kokkos::create_mirror_view(leg.recv_buf);
        if (ns > 0) {
          exec.fence();
          Kokkos::deep_copy(hb, leg.send_buf);
        }
        dec.exchange_face(leg.d, leg.side, hb.data(), int(hb.size()), hrb.data(), int(hrb.size()));
        if (leg.recv_count > 0) Kokkos::deep_copy(leg.recv_buf, hrb);
      }
      if (leg.recv_count > 0)
        moving.unpack(exec, leg.recv_buf, leg.recv_count, leg.recv_first, leg.d, leg.shift);
    }
    exec.fence();
  }
  bool empty() const { return legs_.empty(); }

  /// Particles i < candidates with where(i, d) below `bound` (side 0) or at or above it, in
  /// index order. (Public for CUDA's extended lambdas.)
  static Kokkos::View<int*, Mem> choose(const ExecSpace& exec, const Positions& where,
                                        int candidates, int d, int side, double bound) {
    const auto x = where;
    int count = 0;
    Kokkos::parallel_reduce(
        "amphora::halo::count", kernels::RangePolicy<ExecSpace>(exec, 0, candidates),
        KOKKOS_LAMBDA(int i, int& c) { c += side == 0 ? x(i, d) < bound : x(i, d) >= bound; },
        count);
    Kokkos::View<int*, Mem> send("amphora::halo::send", count);
    Kokkos::parallel_scan(
        "amphora::halo::choose", kernels::RangePolicy<ExecSpace>(exec, 0, candidates),
        KOKKOS_LAMBDA(int i, int& before, bool final) {
          const bool goes = side == 0 ? x(i, d) < bound : x(i, d) >= bound;
          if (final && goes) send(before) = i;
          before += goes;
        });
    return send;
  }

 private:
  struct Leg {
    int d, side;
    Kokkos::View<int*, Mem> send;
    int recv_first = 0, recv_count = 0;
    Kokkos::View<double*, Mem> send_buf, recv_buf;
    int buffer_width = -1;  ///< the record width the buffers hold
    double shift = 0.0;     ///< added to the arriving positions' component d (images)
    bool self = false;      ///< both neighbours along d are this rank: copies on the device
  };
  static bool has_neighbours(const SpatialDecomposition& dec) {
    for (int d = 0; d < 3; ++d)
      for (int side = 0; side < 2; ++side)
        if (dec.neighbor(d, side) >= 0) return true;
    return false;
  }
  static bool self_leg(const SpatialDecomposition& dec, int d) {
    const int r = dec.comm().rank();
    return dec.neighbor(d, 0) == r && dec.neighbor(d, 1) == r;
  }
  std::vector<Leg> legs_;
};

}  // namespace amphora::mesh::particles
