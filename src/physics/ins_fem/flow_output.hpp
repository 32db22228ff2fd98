#pragma once
// The flow's output block for the writers: the Q_k lattice's nodes as a curvilinear grid with
// the velocity components and the pressure at each node (host copies).
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

#include "base/communicator.hpp"
#include "base/output_block.hpp"

namespace amphora::physics::ins_fem {

/// The DoF at lattice node `node` (nodes numbered x fastest).
template <int dim, class Lattice>
long node_dof(const Lattice& lat, long node) {
  int ijk[3] = {0, 0, 0};
  for (int d = 0; d < dim; ++d)
    ijk[d] = static_cast<int>(node % lat.nodes[d]), node /= lat.nodes[d];
  return lat.dof_index(ijk);
}

/// Block `name` of the solver's nodes and fields u, v, (w,) p; the pressure times
/// pressure_scale (1: the solver's kinematic pressure; rho: pascals). On several ranks each
/// writes its slab, the shared node layer included so the pieces join, as "<name>_<rank>".
template <int dim, class Solver>
OutputBlock flow_output_block(const Solver& solver, const std::string& name,
                              double pressure_scale = 1.0) {
  const auto& space = solver.space();
  const auto& lat = space.lattice();
  const long n_nodes = lat.n_nodes(), n = solver.n_dofs();
  auto xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), space.coordinates());
  auto sh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver.state());
  const Communicator& comm = solver.distributed_space().communicator();
  OutputBlock b;
  b.name = comm.size() > 1 ? name + "_" + std::to_string(comm.rank()) : name;
  b.curvilinear = true;
  for (int d = 0; d < dim; ++d) b.nodes[d] = lat.nodes[d];
  b.x.resize(n_nodes);
  b.y.resize(n_nodes);
  b.z.assign(n_nodes, 0.0);
  std::vector<std::vector<double>> f(dim + 1, std::vector<double>(n_nodes));
  for (long node = 0; node < n_nodes; ++node) {
    b.x[node] = xh(node);
    b.y[node] = xh(n_nodes + node);
    if (dim == 3) b.z[node] = xh(2 * n_nodes + node);
    const long dof = node_dof<dim>(lat, node);
    for (int c = 0; c < dim; ++c) f[c][node] = sh(c * n + dof);
    f[dim][node] = pressure_scale * sh(dim * n + dof);
  }
  const char* names[3] = {"u", "v", "w"};
  for (int c = 0; c < dim; ++c) b.fields.push_back({names[c], f[c]});
  b.fields.push_back({"p", f[dim]});
  return b;
}

/// A scalar Q_k field (one value per DoF, host copy) at the block's nodes, in its order.
template <int dim, class Space, class Field>
std::vector<double> node_values(const Space& space, const Field& field) {
  const auto& lat = space.lattice();
  auto fh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), field);
  std::vector<double> out(lat.n_nodes());
  for (long node = 0; node < lat.n_nodes(); ++node) {
    out[node] = fh(node_dof<dim>(lat, node));
  }
  return out;
}

}  // namespace amphora::physics::ins_fem
