// The scene table [water_mac]: every key with its default, unit, range and help.
#include "physics/water_mac/water_mac.hpp"

#include <string>

namespace amphora::physics::water_mac {

ParamTable parameter_table() {
  return {
      "water_mac",
      "water on a uniform MAC grid: level set, semi-Lagrangian advection, ghost-fluid pressure "
      "projection",
      {
          string_param("scene", std::string("dam_break"), "initial state",
                       {"dam_break", "wet_dam_break", "splash", "still"}),
          int_param("cells_x", 64, at_least(2) & at_most(2048), "cells along x"),
          int_param("cells_y", 32, at_least(2) & at_most(2048), "cells along y (up)"),
          int_param("cells_z", 4, at_least(2) & at_most(2048), "cells along z"),
          real_param("length_x", 0.2286, "m", above(0.0),
                     "box length along x (the cell width is length_x / cells_x)"),
          real_param("gravity", 9.81, "m/s^2", at_least(0.0),
                     "gravitational acceleration (along -y)"),
          real_param("density", 1000.0, "kg/m^3", above(0.0), "water density"),
          real_param(
              "cfl", 1.0, "1", above(0.0) & at_most(2.0),
              "largest CFL number of a sub-step (semi-Lagrangian: the trace length in cells)"),
          string_param("solver", std::string("multigrid"), "pressure back end",
                       {"multigrid", "hypre", "mic0"}),
          real_param("tolerance", 1e-8, "1", above(0.0) & below(1.0),
                     "relative residual of the pressure solve"),
          int_param("max_iterations", 500, at_least(1), "pressure CG iteration limit"),
          int_param("reinitialise_iterations", 2, at_least(0),
                    "pseudo-time steps of level-set reinitialisation per sub-step"),
          int_param("optical_depth", 0, at_least(0),
                    "uniform cells below the surface before the tall cells (0: no tall cells)"),
          real_param("column_width", 0.05715, "m", above(0.0),
                     "dam breaks: width a of the water column behind the dam at x = a (the dry-bed "
                     "column is 2a high)"),
          real_param("reservoir_depth", 0.1, "m", above(0.0),
                     "wet dam break: depth of the water behind the dam"),
          real_param("tailwater_depth", 0.01, "m", above(0.0),
                     "wet dam break: depth of the still water ahead of the dam"),
          real_param("pool_depth", 0.6, "m", above(0.0),
                     "splash and still water: depth of the water above y = 0"),
          real_param("drop_radius", 0.08, "m", above(0.0),
                     "splash: radius of the falling ball of water"),
          real_param("drop_height", 0.85, "m", above(0.0), "splash: height of the ball's centre"),
          real_param("drop_speed", 2.0, "m/s", at_least(0.0),
                     "splash: initial downward speed of the ball"),
          real_param("terrain_amplitude", 0.0, "m", at_least(0.0),
                     "still/splash: amplitude of the sinusoidal bottom"),
          real_param("terrain_base", 0.0, "m", at_least(0.0),
                     "still/splash: mean height of the bottom"),
      }};
}

}  // namespace amphora::physics::water_mac
