// DemSystem's state as host arrays: what a checkpoint saves and restores, and the host copies
// insertion works on.
#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/dem/dem_system.hpp"

namespace amphora::physics::dem {

template <class ExecSpace>
typename DemSystem<ExecSpace>::HostArrays DemSystem<ExecSpace>::to_host() const {
  auto copy = [](const auto& view) {
    return Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), view);
  };
  return {copy(p_.x),     copy(p_.v),        copy(p_.omega),   copy(p_.force),   copy(p_.torque),
          copy(x_build_), copy(p_.radius),   copy(p_.mass),    copy(p_.inertia), copy(p_.material),
          copy(p_.gid),   copy(wall_shear_), copy(rec_shear_), copy(rec_gid_)};
}

template <class ExecSpace>
void DemSystem<ExecSpace>::from_host(const HostArrays& h) {
  Kokkos::deep_copy(p_.x, h.x);
  Kokkos::deep_copy(p_.v, h.v);
  Kokkos::deep_copy(p_.omega, h.omega);
  Kokkos::deep_copy(p_.force, h.force);
  Kokkos::deep_copy(p_.torque, h.torque);
  Kokkos::deep_copy(x_build_, h.x_build);
  Kokkos::deep_copy(p_.radius, h.radius);
  Kokkos::deep_copy(p_.mass, h.mass);
  Kokkos::deep_copy(p_.inertia, h.inertia);
  Kokkos::deep_copy(p_.material, h.material);
  Kokkos::deep_copy(p_.gid, h.gid);
  Kokkos::deep_copy(wall_shear_, h.wall_shear);
  Kokkos::deep_copy(rec_shear_, h.rec_shear);
  Kokkos::deep_copy(rec_gid_, h.rec_gid);
}

template <class ExecSpace>
typename DemSystem<ExecSpace>::HostState DemSystem<ExecSpace>::save() const {
  synchronize();
  HostState s;
  auto* self = const_cast<DemSystem*>(this);
  self->history_to_records();
  const int n = p_.n_owned, nw = int(wall_shear_.extent(1)), K = config_.max_contacts;
  const HostArrays h = to_host();
  const auto &x = h.x, &v = h.v, &om = h.omega, &f = h.force, &tq = h.torque, &xb = h.x_build;
  const auto& r = h.radius;
  const auto& mat = h.material;
  const auto& gid = h.gid;
  const auto& ws = h.wall_shear;
  const auto& rg = h.rec_gid;
  const auto& rs = h.rec_shear;
  // Before the first rebuild there are no build positions yet.
  const bool built = has_lists() && n > 0;
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) {
      s.x_build.push_back(built ? xb(i, d) : x(i, d));
      s.x.push_back(x(i, d));
      s.v.push_back(v(i, d));
      s.omega.push_back(om(i, d));
      s.force.push_back(f(i, d));
      s.torque.push_back(tq(i, d));
    }
    s.radius.push_back(r(i));
    s.material.push_back(mat(i));
    s.gid.push_back(gid(i));
    for (int w = 0; w < nw; ++w)
      for (int d = 0; d < 3; ++d) s.wall_shear.push_back(ws(i, w, d));
    for (int c = 0; c < K; ++c) {
      s.contact_gid.push_back(rg(i, c));
      for (int d = 0; d < 3; ++d) s.contact_shear.push_back(rs(i, c, d));
    }
  }
  return s;
}

template <class ExecSpace>
void DemSystem<ExecSpace>::load(const HostState& s) {
  pending_kick_ = false;
  const int nw = int(wall_shear_.extent(1)), K = config_.max_contacts;
  const int total = static_cast<int>(s.radius.size());
  std::vector<int> mine;
  for (int i = 0; i < total; ++i)
    if (decomposition_.owner(&s.x[3 * size_t(i)]) == comm_.rank()) mine.push_back(i);
  const int n = static_cast<int>(mine.size());
  p_.n_owned = p_.n_ghost = 0;
  resize_owned(n);
  clear_external_force(0, n);
  HostArrays h = to_host();
  auto &x = h.x, &v = h.v, &om = h.omega, &f = h.force, &tq = h.torque, &xb = h.x_build;
  auto &r = h.radius, &m = h.mass, &in = h.inertia;
  auto& mat = h.material;
  auto& gid = h.gid;
  auto& ws = h.wall_shear;
  auto& rg = h.rec_gid;
  auto& rs = h.rec_shear;
  const bool have_build = s.x_build.size() == s.x.size();
  for (int a = 0; a < n; ++a) {
    const size_t i = mine[a];
    for (int d = 0; d < 3; ++d) {
      xb(a, d) = have_build ? s.x_build[3 * i + d] : s.x[3 * i + d];
      x(a, d) = s.x[3 * i + d];
      v(a, d) = s.v[3 * i + d];
      om(a, d) = s.omega[3 * i + d];
      f(a, d) = s.force[3 * i + d];
      tq(a, d) = s.torque[3 * i + d];
    }
    r(a) = s.radius[i];
    mat(a) = s.material[i];
    gid(a) = s.gid[i];
    m(a) = config_.materials[mat(a)].density * 4.0 / 3.0 * M_PI * r(a) * r(a) * r(a);
    in(a) = 0.4 * m(a) * r(a) * r(a);
    for (int w = 0; w < nw; ++w)
      for (int d = 0; d < 3; ++d) ws(a, w, d) = s.wall_shear[(i * nw + w) * 3 + d];
    for (int c = 0; c < K; ++c) {
      rg(a, c) = s.contact_gid[i * K + c];
      for (int d = 0; d < 3; ++d) rs(a, c, d) = s.contact_shear[(i * K + c) * 3 + d];
    }
  }
  from_host(h);
  p_.n_owned = n;
  list_.n_rows = list_.n_entries = 0;  // no lists until the next rebuild (arrays kept)
  // Forces of the saved state are restored as they were. The next step rebuilds after its
  // first half kick, at the saved build positions unless a rebuild is due anyway: the lists,
  // ghosts and rows' order (so the order of every sum) are those of the run it continues, on
  // any rank count, and the history comes back from the records.
  keep_build_positions_ = have_build;
  forces_valid_ = true;
}

#define AMPHORA_DEM_CHECKPOINT(E)                                                  \
  template typename DemSystem<E>::HostArrays DemSystem<E>::to_host() const;        \
  template void DemSystem<E>::from_host(const typename DemSystem<E>::HostArrays&); \
  template typename DemSystem<E>::HostState DemSystem<E>::save() const;            \
  template void DemSystem<E>::load(const typename DemSystem<E>::HostState&);
AMPHORA_FOR_EACH_EXEC_SPACE(AMPHORA_DEM_CHECKPOINT)

}  // namespace amphora::physics::dem
