#include "physics/dem/insertion.hpp"

#include <cmath>
#include <sstream>

namespace amphora::physics::dem {

namespace {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

int pick_material(double u, const std::vector<double>& fractions) {
  double acc = 0;
  for (size_t m = 0; m < fractions.size(); ++m) {
    acc += fractions[m];
    if (u < acc) return static_cast<int>(m);
  }
  return static_cast<int>(fractions.size()) - 1;
}

}  // namespace

double uniform01(std::uint64_t seed, std::uint64_t event, std::uint64_t draw) {
  const std::uint64_t h = splitmix64(splitmix64(splitmix64(seed) ^ event) ^ draw);
  return double(h >> 11) * (1.0 / 9007199254740992.0);
}

bool InsertionRegion::contains(const double x[3], double r) const {
  if (x[1] + r > y_max) return false;
  if (kind == kBox) {
    for (int d = 0; d < 3; ++d)
      if (x[d] - r < lo[d] || x[d] + r > hi[d]) return false;
    return true;
  }
  if (x[2] - r < lo[2] || x[2] + r > hi[2]) return false;
  const double dx = x[0] - cx, dy = x[1] - cy;
  return std::sqrt(dx * dx + dy * dy) + r <= radius;
}

double InsertionRegion::volume() const {
  if (kind == kBox) return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
  // Circular segment below y_max times the length.
  const double h = std::min(std::max(y_max - (cy - radius), 0.0), 2 * radius);
  const double r = radius;
  const double area = r * r * std::acos((r - h) / r) - (r - h) * std::sqrt(2 * r * h - h * h);
  return area * (hi[2] - lo[2]);
}

std::vector<ParticleSpec> lattice_insertion(const InsertionRegion& region,
                                            const RadiusDistribution& radii, double spacing,
                                            long long count, double jitter, std::uint64_t seed,
                                            std::int64_t first_gid,
                                            const std::vector<double>& material_fractions,
                                            const std::array<bool, 3>& periodic) {
  if (spacing < 2 * radii.max() * (1 + 1e-12)) {
    std::ostringstream m;
    m << "lattice insertion cannot fit: spacing " << spacing << " m is below the largest "
      << "diameter " << 2 * radii.max() << " m";
    throw InsertionError(m.str());
  }
  std::vector<ParticleSpec> out;
  const double r0 = radii.max();
  int n[3];
  double step[3], first[3];
  for (int d = 0; d < 3; ++d) {
    const double length = region.hi[d] - region.lo[d];
    n[d] = periodic[d] ? std::max(1, int(length / spacing))
                       : std::max(0, int((length - 2 * r0) / spacing) + 1);
    step[d] = periodic[d] ? length / n[d] : spacing;
    first[d] = region.lo[d] + (periodic[d] ? 0.5 * step[d] : r0);
  }
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        if (count > 0 && (long long)out.size() >= count) return out;
        const std::uint64_t id = out.size();
        ParticleSpec p;
        const int idx[3] = {i, j, k};
        for (int d = 0; d < 3; ++d)
          p.x[d] =
              first[d] + idx[d] * step[d] +
              jitter *
                  (uniform01(seed, 1000 + d, id + 7919ULL * (i + 31ULL * (j + 31ULL * k))) - 0.5);
        p.radius = radii.mean * (1 + radii.spread * (2 * uniform01(seed, 2000, id) - 1));
        double probe[3];  // periodic directions: a site may straddle the face
        for (int d = 0; d < 3; ++d)
          probe[d] = periodic[d] ? 0.5 * (region.lo[d] + region.hi[d]) : p.x[d];
        if (!region.contains(probe, r0 + jitter)) continue;
        p.material = pick_material(uniform01(seed, 3000, id), material_fractions);
        p.gid = first_gid + static_cast<std::int64_t>(out.size());
        out.push_back(p);
      }
  if (count > 0 && (long long)out.size() < count) {
    std::ostringstream m;
    m << "lattice insertion cannot fit " << count << " particles: the region holds " << out.size()
      << " lattice sites of spacing " << spacing << " m";
    throw InsertionError(m.str());
  }
  return out;
}

template <class ExecSpace>
std::vector<ParticleSpec> random_insertion(const DemSystem<ExecSpace>& system,
                                           const InsertionRegion& region,
                                           const RadiusDistribution& radii, long long count,
                                           int attempts, std::uint64_t seed, std::uint64_t event,
                                           std::int64_t first_gid,
                                           const std::vector<double>& material_fractions) {
  // Existing particles near the region, from every rank (x, y, z, r).
  const auto& p = system.particles();
  auto x = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.x);
  auto r = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.radius);
  const double margin = 2 * radii.max();
  // Periodic directions: distances to the nearest image (every particle may be near one).
  const auto& cfg = system.config();
  const auto per = cfg.periodic;
  double length[3];
  for (int d = 0; d < 3; ++d) length[d] = cfg.domain_hi[d] - cfg.domain_lo[d];
  const auto gap = [&](const double* a, const double* b) {
    double d2 = 0;
    for (int d = 0; d < 3; ++d) {
      double dx = a[d] - b[d];
      if (per[d]) dx -= length[d] * std::round(dx / length[d]);
      d2 += dx * dx;
    }
    return d2;
  };
  std::vector<double> near;
  for (int i = 0; i < p.n_owned; ++i) {
    bool inside = true;
    for (int d = 0; d < 3; ++d)
      inside = inside &&
               (per[d] || (x(i, d) > region.lo[d] - margin && x(i, d) < region.hi[d] + margin));
    if (inside) {
      for (int d = 0; d < 3; ++d) near.push_back(x(i, d));
      near.push_back(r(i));
    }
  }
  const std::vector<double> all = system.decomposition().comm().allgatherv(near);
  std::vector<ParticleSpec> out;
  const long long draws = static_cast<long long>(attempts) * count;
  for (long long a = 0; a < draws && (long long)out.size() < count; ++a) {
    ParticleSpec c;
    const std::uint64_t d0 = 5 * static_cast<std::uint64_t>(a);
    c.radius = radii.mean * (1 + radii.spread * (2 * uniform01(seed, event, d0) - 1));
    for (int d = 0; d < 3; ++d)
      c.x[d] = region.lo[d] + c.radius +
               (region.hi[d] - region.lo[d] - 2 * c.radius) * uniform01(seed, event, d0 + 1 + d);
    if (!region.contains(c.x, c.radius)) continue;
    bool free = true;
    for (size_t k = 0; free && k < all.size(); k += 4)
      free = gap(c.x, &all[k]) >= (c.radius + all[k + 3]) * (c.radius + all[k + 3]);
    for (size_t k = 0; free && k < out.size(); ++k)
      free = gap(c.x, out[k].x) >= (c.radius + out[k].radius) * (c.radius + out[k].radius);
    if (!free) continue;
    c.material = pick_material(uniform01(seed, event, d0 + 4), material_fractions);
    c.gid = first_gid + static_cast<std::int64_t>(out.size());
    out.push_back(c);
  }
  if ((long long)out.size() < count) {
    std::ostringstream m;
    m << "random insertion cannot fit " << count << " particles in the insertion region after "
      << draws << " draws (placed " << out.size() << "); lower the rate or the count, or enlarge "
      << "the region";
    throw InsertionError(m.str());
  }
  return out;
}

// on every enabled execution space, as DemSystem is (the module calls it on the default one)
#define AMPHORA_RANDOM_INSERTION_ON(SPACE)                                                        \
  template std::vector<ParticleSpec> random_insertion(                                            \
      const DemSystem<SPACE>&, const InsertionRegion&, const RadiusDistribution&, long long, int, \
      std::uint64_t, std::uint64_t, std::int64_t, const std::vector<double>&);
AMPHORA_IF_SERIAL(AMPHORA_RANDOM_INSERTION_ON(Kokkos::Serial))
AMPHORA_IF_OPENMP(AMPHORA_RANDOM_INSERTION_ON(Kokkos::OpenMP))
AMPHORA_IF_CUDA(AMPHORA_RANDOM_INSERTION_ON(Kokkos::Cuda))
AMPHORA_IF_HIP(AMPHORA_RANDOM_INSERTION_ON(Kokkos::Experimental::HIP))
#undef AMPHORA_RANDOM_INSERTION_ON

}  // namespace amphora::physics::dem
