#pragma once
// Stoker's wet-bed dam break in shallow water (Stoker 1957, "Water Waves", sec. 10.8): water at
// rest, h0 deep behind the dam and h1 deep ahead of it (0 < h1 < h0). When the dam goes, a
// rarefaction runs back into the reservoir and a bore runs forward into the still water; between
// them the depth is hm and the velocity um, both constant. The bore's speed S follows from
//   across the rarefaction (Riemann invariant):  um + 2 sqrt(g hm) = 2 sqrt(g h0),
//   across the bore (mass and momentum):         S = sqrt(g hm (hm + h1) / (2 h1)),
//                                                 um = S (1 - h1 / hm),
// solved here for hm by bisection (the residual is monotone in hm on (h1, h0)).
#include <cmath>
#include <stdexcept>
#include <string>

namespace amphora::physics::water_mac {

struct StokerDamBreak {
  double hm = 0.0;          ///< depth between the rarefaction and the bore
  double um = 0.0;          ///< velocity there
  double bore_speed = 0.0;  ///< S: the bore is at x_dam + S t
};

inline StokerDamBreak stoker_dam_break(double g, double h0, double h1) {
  if (!(g > 0.0 && h1 > 0.0 && h1 < h0))
    throw std::invalid_argument(
        "stoker_dam_break: needs g > 0 and 0 < h1 < h0 (g = " + std::to_string(g) +
        ", h0 = " + std::to_string(h0) + ", h1 = " + std::to_string(h1) + ")");
  const auto bore = [&](double hm) { return std::sqrt(g * hm * (hm + h1) / (2.0 * h1)); };
  // rarefaction velocity minus bore velocity: positive at hm = h1, negative at hm = h0
  const auto residual = [&](double hm) {
    return 2.0 * (std::sqrt(g * h0) - std::sqrt(g * hm)) - bore(hm) * (1.0 - h1 / hm);
  };
  double lo = h1, hi = h0;
  for (int it = 0; it < 200 && hi - lo > 1e-15 * h0; ++it) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid) > 0.0 ? lo : hi) = mid;
  }
  StokerDamBreak s;
  s.hm = 0.5 * (lo + hi);
  s.bore_speed = bore(s.hm);
  s.um = 2.0 * (std::sqrt(g * h0) - std::sqrt(g * s.hm));
  return s;
}

}  // namespace amphora::physics::water_mac
