#pragma once
// The per-particle arrays a migration or a halo carries, packed on the device as doubles
// (integers and ids exactly: all are below 2^53), each particle's record `width()` doubles
// long. Positions (add_position) may be shifted as they are unpacked: a periodic image's
// record arrives moved by the box's length. A ParticleFields sees the arrays as they are when it is
// made: make a new one after an array is reallocated (grown, permuted).
#include <functional>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "kernels/spaces.hpp"

namespace amphora::mesh::particles {

template <class ExecSpace>
class ParticleFields {
 public:
  using Mem = typename ExecSpace::memory_space;
  using Buffer = Kokkos::View<double*, Mem>;
  using Indices = Kokkos::View<int*, Mem>;

  /// Adds an array whose particle i is the contiguous row i (rank 1, or LayoutRight).
  template <class View>
  ParticleFields& add(const View& v) {
    static_assert(
        View::rank == 1 || std::is_same_v<typename View::array_layout, Kokkos::LayoutRight>,
        "a particle's row must be contiguous");
    int inner = 1;
    for (unsigned r = 1; r < View::rank; ++r) inner *= static_cast<int>(v.extent(r));
    using T = typename View::non_const_value_type;
    if (std::is_same_v<T, double> && doubles_.count < Doubles::max) {  // one kernel for these
      doubles_.data[doubles_.count] = reinterpret_cast<double*>(v.data());
      doubles_.inner[doubles_.count] = inner;
      doubles_.position[doubles_.count] = false;
      doubles_.offset[doubles_.count++] = width_;
    } else {
      fields_.push_back({packer(v.data(), inner, width_), unpacker(v.data(), inner, width_)});
    }
    width_ += inner;
    return *this;
  }
  /// Adds an (n, 3) array of positions: unpack's shift applies to it.
  template <class View>
  ParticleFields& add_position(const View& v) {
    static_assert(std::is_same_v<typename View::non_const_value_type, double> && View::rank == 2,
                  "positions are (n, 3) doubles");
    if (doubles_.count == Doubles::max || v.extent(1) != 3)
      throw std::logic_error("ParticleFields: positions must be (n, 3), at most 16 arrays");
    add(v);
    doubles_.position[doubles_.count - 1] = true;
    return *this;
  }
  int width() const { return width_; }

  /// buf(k * width() + ...) = the record of particle which(k), k < count.
  void pack(const ExecSpace& exec, const Indices& which, int count, const Buffer& buf) const {
    if (doubles_.count > 0)
      Kokkos::parallel_for("amphora::particles::pack_doubles",
                           kernels::RangePolicy<ExecSpace>(exec, 0, count),
                           PackDoubles{doubles_, which, buf, width_});
    for (const auto& f : fields_) f.pack(exec, which, count, buf, width_);
  }
  /// Particles first .. first + count from the records in buf, the positions' component
  /// `shift_dim` (if >= 0) moved by `shift`.
  void unpack(const ExecSpace& exec, const Buffer& buf, int count, int first, int shift_dim = -1,
              double shift = 0.0) const {
    if (doubles_.count > 0)
      Kokkos::parallel_for("amphora::particles::unpack_doubles",
                           kernels::RangePolicy<ExecSpace>(exec, 0, count),
                           UnpackDoubles{doubles_, buf, width_, first, shift_dim, shift});
    for (const auto& f : fields_) f.unpack(exec, buf, count, first, width_);
  }

  /// The double arrays, packed by one kernel.
  struct Doubles {
    static constexpr int max = 16;
    int count = 0;
    double* data[max];
    int inner[max], offset[max];
    bool position[max];
  };
  struct PackDoubles {
    Doubles f;
    Indices which;
    Buffer buf;
    int w;
    KOKKOS_INLINE_FUNCTION void operator()(int k) const {
      const size_t i = size_t(which(k)), to = size_t(k) * w;
      for (int a = 0; a < f.count; ++a)
        for (int c = 0; c < f.inner[a]; ++c)
          buf(to + f.offset[a] + c) = f.data[a][i * f.inner[a] + c];
    }
  };
  struct UnpackDoubles {
    Doubles f;
    Buffer buf;
    int w, first, shift_dim;
    double shift;
    KOKKOS_INLINE_FUNCTION void operator()(int k) const {
      const size_t i = size_t(first + k), from = size_t(k) * w;
      for (int a = 0; a < f.count; ++a)
        for (int c = 0; c < f.inner[a]; ++c) {
          const double s = f.position[a] && c == shift_dim ? shift : 0.0;
          const double value = buf(from + f.offset[a] + c);
          f.data[a][i * f.inner[a] + c] = s == 0.0 ? value : value + s;
        }
    }
  };
  /// Device functors (not lambdas: nvcc takes no extended lambda inside a host lambda).
  template <class T>
  struct PackKernel {
    T* data;
    Indices which;
    Buffer buf;
    int inner, offset, w;
    KOKKOS_INLINE_FUNCTION void operator()(int k) const {
      const size_t from = size_t(which(k)) * inner, to = size_t(k) * w + offset;
      for (int c = 0; c < inner; ++c) buf(to + c) = static_cast<double>(data[from + c]);
    }
  };
  template <class T>
  struct UnpackKernel {
    T* data;
    Buffer buf;
    int inner, offset, w, first;
    KOKKOS_INLINE_FUNCTION void operator()(int k) const {
      const size_t to = size_t(first + k) * inner, from = size_t(k) * w + offset;
      for (int c = 0; c < inner; ++c) data[to + c] = static_cast<T>(buf(from + c));
    }
  };
  using PackFn = std::function<void(const ExecSpace&, const Indices&, int, const Buffer&, int)>;
  using UnpackFn = std::function<void(const ExecSpace&, const Buffer&, int, int, int)>;
  template <class T>
  static PackFn packer(T* data, int inner, int offset) {
    return [=](const ExecSpace& exec, const Indices& which, int count, const Buffer& buf, int w) {
      Kokkos::parallel_for("amphora::particles::pack",
                           kernels::RangePolicy<ExecSpace>(exec, 0, count),
                           PackKernel<T>{data, which, buf, inner, offset, w});
    };
  }
  template <class T>
  static UnpackFn unpacker(T* data, int inner, int offset) {
    return [=](const ExecSpace& exec, const Buffer& buf, int count, int first, int w) {
      Kokkos::parallel_for("amphora::particles::unpack",
                           kernels::RangePolicy<ExecSpace>(exec, 0, count),
                           UnpackKernel<T>{data, buf, inner, offset, w, first});
    };
  }

 private:
  struct Field {
    PackFn pack;
    UnpackFn unpack;
  };
  Doubles doubles_;
  std::vector<Field> fields_;
  int width_ = 0;
};

}  // namespace amphora::mesh::particles
