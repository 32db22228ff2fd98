// DemSystem's diagnostics: energies, contacts and overlaps in one reduction, the contact pairs
// and counts, the first non-finite particle.
#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/dem/dem_system.hpp"
#include "physics/dem/hertz_mindlin.hpp"

namespace amphora::physics::dem {

template <class ExecSpace>
std::vector<std::pair<std::int64_t, std::int64_t>> DemSystem<ExecSpace>::contact_pairs() const {
  auto off = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), list_.offsets);
  auto nbr = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), list_.neighbors);
  auto x = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p_.x);
  auto r = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p_.radius);
  auto gid = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p_.gid);
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
  for (int i = 0; i < p_.n_owned; ++i) {
    for (int k = off(i); k < off(i + 1); ++k) {
      const int j = nbr(k);
      double d2 = 0;
      for (int d = 0; d < 3; ++d) d2 += (x(j, d) - x(i, d)) * (x(j, d) - x(i, d));
      const double rs = r(i) + r(j);
      if (d2 < rs * rs && gid(i) < gid(j)) pairs.emplace_back(gid(i), gid(j));
    }
  }
  return pairs;
}

template <class ExecSpace>
DemDiagnostics DemSystem<ExecSpace>::diagnostics() const {
  synchronize();
  const int n = p_.n_owned;
  const auto x = p_.x, v = p_.v, om = p_.omega;
  const auto rad = p_.radius, mass = p_.mass, in = p_.inertia;
  const auto mat = p_.material;
  const auto off = list_.offsets;
  const auto nbr = list_.neighbors;
  const auto pairs = pairs_;
  const auto walls = walls_;
  const int nw = n_walls_;
  const double t = time_;
  const double g0 = config_.gravity[0], g1 = config_.gravity[1], g2 = config_.gravity[2];
  const bool have_list = has_lists();
  // One pass over the owned particles: energies, contacts (each pair seen from both sides) and
  // the largest overlaps, of pairs and of walls.
  double ke = 0, re = 0, pe = 0, el = 0, mo = 0, wel = 0, wmo = 0;
  long long contacts = 0, wcontacts = 0;
  Kokkos::parallel_reduce(
      "amphora::dem::diagnostics", kernels::RangePolicy<ExecSpace>(exec_, 0, n),
      KOKKOS_LAMBDA(int i, double& k, double& r, double& p, double& e, long long& c, double& m,
                    double& we, long long& wc, double& wm) {
        k += 0.5 * mass(i) * (v(i, 0) * v(i, 0) + v(i, 1) * v(i, 1) + v(i, 2) * v(i, 2));
        r += 0.5 * in(i) * (om(i, 0) * om(i, 0) + om(i, 1) * om(i, 1) + om(i, 2) * om(i, 2));
        p -= mass(i) * (g0 * x(i, 0) + g1 * x(i, 1) + g2 * x(i, 2));
        for (int a = have_list ? off(i) : 0; have_list && a < off(i + 1); ++a) {
          const int j = nbr(a);
          double d2 = 0;
          for (int d = 0; d < 3; ++d) d2 += (x(j, d) - x(i, d)) * (x(j, d) - x(i, d));
          const double rs = rad(i) + rad(j);
          if (d2 >= rs * rs) continue;
          const double delta = rs - kernels::math::sqrt(d2), reff = rad(i) * rad(j) / rs;
          e += hertz_energy(0.5, pairs(mat(i), mat(j)).e_star, reff, delta);
          ++c;
          m = kernels::math::max(
              m, (rs - kernels::math::sqrt(d2)) / kernels::math::min(rad(i), rad(j)));
        }
        const double xi[3] = {x(i, 0), x(i, 1), x(i, 2)};
        for (int w = 0; w < nw; ++w) {
          double nn[3], delta, vw[3];
          if (!wall_contact(walls(w), t, xi, rad(i), nn, delta, vw)) continue;
          we += hertz_energy(1.0, pairs(mat(i), walls(w).material).e_star, rad(i), delta);
          ++wc;
          wm = kernels::math::max(wm, delta / rad(i));
        }
      },
      ke, re, pe, el, contacts, Kokkos::Max<double>(mo), wel, wcontacts, Kokkos::Max<double>(wmo));
  DemDiagnostics out;
  out.particles = comm_.sum(static_cast<long long>(n));
  out.contacts = comm_.sum(contacts) / 2;
  out.wall_contacts = comm_.sum(wcontacts);
  out.kinetic = comm_.sum(ke);
  out.rotational = comm_.sum(re);
  out.gravity_potential = comm_.sum(pe);
  out.elastic = comm_.sum(el + wel);
  // 0 without contacts (the Max reductions' identity is the lowest double)
  out.max_overlap = std::max(0.0, comm_.max(std::max(mo, wmo)));
  return out;
}

template <class ExecSpace>
std::vector<int> DemSystem<ExecSpace>::contact_counts() const {
  const int n = p_.n_owned;
  Kokkos::View<int*, Mem> counts("amphora::dem::contact_counts", n);
  const auto x = p_.x;
  const auto rad = p_.radius;
  const auto off = list_.offsets;
  const auto nbr = list_.neighbors;
  const auto walls = walls_;
  const int nw = n_walls_;
  const double t = time_;
  const bool have_list = has_lists();
  Kokkos::parallel_for(
      "amphora::dem::contact_counts", kernels::RangePolicy<ExecSpace>(exec_, 0, n),
      KOKKOS_LAMBDA(int i) {
        int c = 0;
        if (have_list) {
          for (int k = off(i); k < off(i + 1); ++k) {
            const int j = nbr(k);
            double d2 = 0;
            for (int d = 0; d < 3; ++d) d2 += (x(j, d) - x(i, d)) * (x(j, d) - x(i, d));
            const double rs = rad(i) + rad(j);
            if (d2 < rs * rs) ++c;
          }
        }
        const double xi[3] = {x(i, 0), x(i, 1), x(i, 2)};
        for (int w = 0; w < nw; ++w) {
          double nn[3], delta, vw[3];
          if (wall_contact(walls(w), t, xi, rad(i), nn, delta, vw)) ++c;
        }
        counts(i) = c;
      });
  auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), counts);
  return std::vector<int>(h.data(), h.data() + n);
}

template <class ExecSpace>
std::int64_t DemSystem<ExecSpace>::first_nonfinite() const {
  synchronize();
  const auto x = p_.x, v = p_.v;
  const auto gid = p_.gid;
  std::int64_t bad = std::numeric_limits<std::int64_t>::max();
  Kokkos::parallel_reduce(
      "amphora::dem::first_nonfinite", kernels::RangePolicy<ExecSpace>(exec_, 0, p_.n_owned),
      KOKKOS_LAMBDA(int i, std::int64_t& acc) {
        bool ok = true;
        for (int d = 0; d < 3; ++d)
          ok = ok && kernels::math::isfinite(x(i, d)) && kernels::math::isfinite(v(i, d));
        if (!ok && gid(i) < acc) acc = gid(i);
      },
      Kokkos::Min<std::int64_t>(bad));
  long long global = bad;
  MPI_Allreduce(MPI_IN_PLACE, &global, 1, MPI_LONG_LONG, MPI_MIN, comm_.get());
  return global == std::numeric_limits<std::int64_t>::max() ? -1 : global;
}

#define AMPHORA_DEM_DIAGNOSTICS(E)                                                                 \
  template std::vector<std::pair<std::int64_t, std::int64_t>> DemSystem<E>::contact_pairs() const; \
  template DemDiagnostics DemSystem<E>::diagnostics() const;                                       \
  template std::vector<int> DemSystem<E>::contact_counts() const;                                  \
  template std::int64_t DemSystem<E>::first_nonfinite() const;
AMPHORA_FOR_EACH_EXEC_SPACE(AMPHORA_DEM_DIAGNOSTICS)

}  // namespace amphora::physics::dem
