#include "physics/water_mac/water_diagnostics.hpp"

#include <mpi.h>

namespace amphora::physics::water_mac {

double martin_moyce_front(double T) {
  // Martin & Moyce (1952), fig. 3, n^2 = 2, a = 2.25 in (digitised; as tabulated in PySPH's
  // examples/dam_break data module): T = t sqrt(2 g / a), Z = x / a.
  static const double data[][2] = {
      {0.832, 1.217}, {1.219, 1.474},  {1.997, 2.292},  {2.547, 2.995},  {3.345, 4.134},
      {4.034, 4.944}, {4.418, 5.881},  {5.091, 6.980},  {5.685, 7.945},  {6.306, 8.966},
      {6.822, 9.986}, {7.439, 10.963}, {8.031, 11.977}, {8.633, 13.005}, {9.237, 13.970}};
  constexpr int n = sizeof(data) / sizeof(data[0]);
  if (T <= data[0][0]) return data[0][1];
  for (int m = 1; m < n; ++m)
    if (T <= data[m][0]) {
      const double s = (T - data[m - 1][0]) / (data[m][0] - data[m - 1][0]);
      return data[m - 1][1] + s * (data[m][1] - data[m - 1][1]);
    }
  return data[n - 1][1];
}

double dam_break_front(const LevelSetBlock& b) {
  const std::vector<double>& phi = b.phi;
  const kernels::mac::MacGrid& g = b.grid;
  // per z row of the whole grid, the front of this block's part (0 if none), then the largest
  std::vector<double> x(b.global.nz, 0.0);
  for (int k = 0; k < g.nz; ++k) {
    double& xk = x[b.lower[2] + k];
    for (int i = 0; i < g.nx; ++i) {
      const double p0 = phi[g.index(i, 0, k)];
      if (p0 >= 0) continue;
      if (i + 1 == g.nx && b.upper_x_is_box) {
        xk = g.origin[0] + g.nx * g.h;
        continue;
      }
      const double p1 = phi[g.index(i + 1, 0, k)];
      xk = g.origin[0] + (i + 0.5) * g.h + (p1 > 0 ? g.h * p0 / (p0 - p1) : g.h);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, x.data(), b.global.nz, MPI_DOUBLE, MPI_MAX, b.comm.get());
  double sum = 0.0;
  for (const double xk : x) sum += xk;
  return sum / b.global.nz;
}

double bore_position(const LevelSetBlock& b, double half_depth) {
  const std::vector<double>& phi = b.phi;
  const kernels::mac::MacGrid& g = b.grid;
  std::vector<double> depth(b.global.nx, 0.0);  // summed over z, this block's columns
  for (int k = 0; k < g.nz; ++k)
    for (int i = 0; i < g.nx; ++i) {
      // the bottom row dry: no depth; no crossing: water to the top
      double y = phi[g.index(i, 0, k)] >= 0 ? 0.0 : g.ny * g.h;
      for (int j = 0; j + 1 < g.ny && y > 0.0; ++j) {
        const double p0 = phi[g.index(i, j, k)], p1 = phi[g.index(i, j + 1, k)];
        if (p0 < 0 && p1 >= 0) {
          y = (j + 0.5) * g.h + g.h * p0 / (p0 - p1);
          break;
        }
      }
      depth[b.lower[0] + i] += y;
    }
  MPI_Allreduce(MPI_IN_PLACE, depth.data(), b.global.nx, MPI_DOUBLE, MPI_SUM, b.comm.get());
  const double half = half_depth * b.global.nz;
  for (int i = b.global.nx - 2; i >= 0; --i)
    if (depth[i] >= half) {
      const double s =
          depth[i + 1] < depth[i] ? (depth[i] - half) / (depth[i] - depth[i + 1]) : 0.0;
      return b.global.origin[0] + (i + 0.5 + s) * g.h;
    }
  return 0.0;
}

double mean_surface_height(const LevelSetBlock& b) {
  const std::vector<double>& phi = b.phi;
  const kernels::mac::MacGrid& g = b.grid;
  double sum = 0.0;
  for (int k = 0; k < g.nz; ++k)
    for (int i = 0; i < g.nx; ++i) {
      double y = 0.0;
      for (int j = 0; j + 1 < g.ny; ++j) {
        const double p0 = phi[g.index(i, j, k)], p1 = phi[g.index(i, j + 1, k)];
        if (p0 < 0 && p1 >= 0) y = (j + 0.5) * g.h + g.h * p0 / (p0 - p1);
      }
      sum += y;
    }
  return b.comm.sum(sum) / (double(b.global.nx) * b.global.nz);
}

}  // namespace amphora::physics::water_mac
