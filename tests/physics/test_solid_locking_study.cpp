// The locking study of docs/solid_fem.md (label slow): the cantilever's tip deflection against
// the mesh for the per-element and per-node constraints on both splits, against the Q2
// reference. Set AMPHORA_LOCKING_CSV to a path to keep the table
// (scripts/study_solid_locking.py charts it).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "locking_cantilever.hpp"

namespace amphora::test::locking {

TEST(SolidLockingStudy, PerNodeWithinFivePercentOfQ2WherePerElementLocks) {
  const double reference = q2_reference();
  std::FILE* csv = nullptr;
  if (const char* path = std::getenv("AMPHORA_LOCKING_CSV")) csv = std::fopen(path, "w");
  if (csv) std::fprintf(csv, "split,cells_per_side,nodes,tets,per_element,per_node,q2\n");
  const struct {
    Split split;
    const char* name;
    std::vector<int> cells;
  } runs[] = {{Split::kuhn6, "kuhn6", {2, 4, 6, 8, 10, 12}},
              {Split::centred24, "centred24", {1, 2, 3, 4, 6}}};
  for (const auto& run : runs)
    for (const int k : run.cells) {
      const TetCantilever beam(k, run.split);
      const double elem = beam.tip_deflection(Constraint::element, kLambda);
      const double node = beam.tip_deflection(Constraint::node, kLambda);
      std::printf("%s k %d (%d nodes): per element %.4f, per node %.4f of Q2 %.6g\n", run.name, k,
                  beam.mesh.n_nodes(), elem / reference, node / reference, reference);
      if (csv)
        std::fprintf(csv, "%s,%d,%d,%d,%.10g,%.10g,%.10g\n", run.name, k, beam.mesh.n_nodes(),
                     beam.mesh.n_tets(), elem, node, reference);
      if (k == run.cells.back()) {
        EXPECT_LT(std::abs(node - reference), 0.05 * reference) << run.name << " per node";
        if (run.split == Split::kuhn6) {
          EXPECT_LT(elem, 0.5 * reference) << "per element locks";
        }
      }
    }
  if (csv) std::fclose(csv);
}

}  // namespace amphora::test::locking
