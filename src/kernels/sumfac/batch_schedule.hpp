#pragma once
// Schedules of the cell-batch loops: on host spaces blocks of consecutive slabs of cells (a
// slab: a layer of cells along the last direction) are the parallel items, each run in order by
// one thread, in two colours (three for an odd periodic count) so no two concurrent blocks
// share a node; sums are then formed in an order that does not depend on the thread count.
// Device spaces run every batch at once and their bodies add atomically.
#include <cstddef>
#include <type_traits>

#include <Kokkos_Core.hpp>

#include "kernels/spaces.hpp"
#include "kernels/sumfac/qk_lattice.hpp"
#include "kernels/sumfac/row_touch.hpp"

namespace amphora::kernels::sumfac {

/// The block colouring of a lattice's slabs (see the top of this file): colours 0 and 1 take
/// alternate blocks of slabs_per_block() consecutive slabs (the last block may be short), colour
/// 2 the last block of an odd count along a periodic direction. Item i of a colour is one block.
template <int dim>
struct SlabBlockColouring {
  int slabs = 0, run = 1, blocks = 0;
  bool odd_periodic = false;
  explicit SlabBlockColouring(const QkLattice<dim>& lattice)
      : slabs(lattice.n_slabs()),
        run(lattice.slabs_per_block()),
        blocks(lattice.n_slab_blocks()),
        odd_periodic(lattice.block_colour(lattice.n_slab_blocks() - 1) == 2) {}
  int items(int colour) const {
    const int regular = odd_periodic ? blocks - 1 : blocks;
    return colour < 2 ? (regular - colour + 1) / 2 : (odd_periodic ? 1 : 0);
  }
  KOKKOS_INLINE_FUNCTION int first_slab(int colour, int i) const {
    return (colour < 2 ? 2 * i + colour : blocks - 1) * run;
  }
  KOKKOS_INLINE_FUNCTION int end_slab(int colour, int i) const {
    const int end = first_slab(colour, i) + run;
    return end < slabs ? end : slabs;
  }
};

/// Runs body(b) for every batch b so that batches running at once share no node (see the top of
/// this file), calling first_touch(slab, row) before and last_touch(slab, row) after each
/// row of a slab's batches on host spaces (so a destination can be zeroed row by row while it
/// is in cache, and vector work done on the nodes a row reads first or writes last:
/// sumfac/row_touch.hpp). A body taking two ints is called as body(b0, b1) for the batches
/// b0 .. b1 - 1 of one row of cells instead (one batch at a time on devices), so it can form
/// what the row's batches share once.
/// Device spaces run all batches at once: body must add atomically, first_touch and last_touch
/// are not called. Returns whether they were called.
template <class ExecSpace, int dim, class FirstTouch, class Body, class LastTouch = NoTouch>
bool for_each_batch_coloured(const ExecSpace& exec, const QkLattice<dim>& lattice,
                             const char* label, const FirstTouch& first_touch, const Body& body,
                             const LastTouch& last_touch = {}) {
  constexpr bool host = runs_on_host_v<ExecSpace>;
  constexpr bool by_row = std::is_invocable_v<const Body&, int, int>;
  if constexpr (!host) {
    if constexpr (by_row)
      Kokkos::parallel_for(
          label, RangePolicy<ExecSpace>(exec, 0, lattice.n_batches()),
          KOKKOS_LAMBDA(int b) { body(b, b + 1); });
    else
      Kokkos::parallel_for(label, RangePolicy<ExecSpace>(exec, 0, lattice.n_batches()), body);
    return false;
  } else {
    const SlabBlockColouring<dim> colouring(lattice);
    const int per_slab = lattice.batches_per_slab();
    const int rows = lattice.rows_per_slab(), per_row = per_slab / rows;
    for (int colour = 0; colour < 3; ++colour) {
      const int items = colouring.items(colour);
      if (items <= 0) continue;
      // a host lambda: this branch runs on host spaces only (and nvcc's extended lambdas may not
      // first-capture body inside the if constexpr below)
      Kokkos::parallel_for(label, RangePolicy<ExecSpace>(exec, 0, items), [=](int i) {
        for (int slab = colouring.first_slab(colour, i); slab < colouring.end_slab(colour, i);
             ++slab)
          for (int row = 0; row < rows; ++row) {
            first_touch(slab, row);
            const int b0 = slab * per_slab + row * per_row;
            if constexpr (by_row)
              body(b0, b0 + per_row);
            else
              for (int b = b0; b < b0 + per_row; ++b) body(b);
            last_touch(slab, row);
          }
      });
    }
    return true;
  }
}

/// Runs body(team, b, b + 1) for every batch b, one team of team_size (an int or Kokkos::AUTO)
/// per batch, all at once, with scratch_bytes of level-1 team scratch per team: body must add
/// atomically. The schedule of device spaces in for_each_batch_team; on a host space with
/// team_size > 1 it shows that a body shares its work correctly.
template <class ExecSpace, int dim, class TeamSize, class Body>
void for_each_batch_team_at_once(const ExecSpace& exec, const QkLattice<dim>& lattice,
                                 const char* label, std::size_t scratch_bytes, TeamSize team_size,
                                 const Body& body) {
  using Policy = Kokkos::TeamPolicy<ExecSpace>;
  Policy policy(exec, lattice.n_batches(), team_size);
  policy.set_scratch_size(1, Kokkos::PerTeam(scratch_bytes));
  Kokkos::parallel_for(
      label, policy, KOKKOS_LAMBDA(const typename Policy::member_type& team) {
        body(team, team.league_rank(), team.league_rank() + 1);
      });
}

/// Runs body(team, b0, b1) on the batches b0 .. b1 - 1 with one team per call and scratch_bytes
/// of level-1 team scratch per team, for bodies whose team shares each batch's work (a team's
/// scratch is taken once per call: it is not returned within it). On host spaces a team of one
/// thread takes one block of slabs, blocks coloured as above; device spaces run one team per
/// batch, all at once (for_each_batch_team_at_once), and body must add atomically.
template <class ExecSpace, int dim, class Body>
void for_each_batch_team(const ExecSpace& exec, const QkLattice<dim>& lattice, const char* label,
                         std::size_t scratch_bytes, const Body& body) {
  using Policy = Kokkos::TeamPolicy<ExecSpace>;
  constexpr bool host = runs_on_host_v<ExecSpace>;
  if constexpr (!host) {
    for_each_batch_team_at_once(exec, lattice, label, scratch_bytes, Kokkos::AUTO, body);
  } else {
    const SlabBlockColouring<dim> colouring(lattice);
    const int per_slab = lattice.batches_per_slab();
    for (int colour = 0; colour < 3; ++colour) {
      const int items = colouring.items(colour);
      if (items <= 0) continue;
      Policy policy(exec, items, 1);
      policy.set_scratch_size(1, Kokkos::PerTeam(scratch_bytes));
      Kokkos::parallel_for(
          label, policy, KOKKOS_LAMBDA(const typename Policy::member_type& team) {
            const int i = team.league_rank();
            body(team, colouring.first_slab(colour, i) * per_slab,
                 colouring.end_slab(colour, i) * per_slab);
          });
    }
  }
}

}  // namespace amphora::kernels::sumfac
