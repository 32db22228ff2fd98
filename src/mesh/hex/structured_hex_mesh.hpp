#pragma once
// A structured box of hexahedra (quadrilaterals in 2D) with, per face, a periodic, Dirichlet or
// Neumann condition, and an optional smooth deformation map x = phi(X) of the box that curves
// the cells (applied to every node of a Q_k space, so the geometry is isoparametric).
#include <array>
#include <functional>
#include <string>

namespace amphora::mesh::hex {

/// `interface`: a face this box shares with a neighbouring rank's box (DistributedQkSpace):
/// natural for an operator, like Neumann, but its nodes belong to cells on both sides.
enum class FaceCondition { dirichlet, neumann, periodic, interface };

using Point3 = std::array<double, 3>;

template <int dim>
struct StructuredHexMesh {
  static_assert(dim == 2 || dim == 3, "dim must be 2 or 3");
  std::array<int, 3> cells{1, 1, 1};
  Point3 lower{0.0, 0.0, 0.0};
  Point3 upper{1.0, 1.0, 1.0};
  /// faces[2d] is x_d = lower[d], faces[2d+1] is x_d = upper[d]; periodic must come in pairs.
  std::array<FaceCondition, 6> faces{FaceCondition::dirichlet, FaceCondition::dirichlet,
                                     FaceCondition::dirichlet, FaceCondition::dirichlet,
                                     FaceCondition::dirichlet, FaceCondition::dirichlet};
  /// Maps the box to the physical domain; empty: the identity (Cartesian cells).
  std::function<Point3(const Point3&)> deformation;
  /// The deformation is affine (every cell is a parallelepiped): per-cell geometry suffices.
  bool affine_deformation = false;

  bool periodic(int d) const { return faces[2 * d] == FaceCondition::periodic; }
  bool cartesian() const { return !deformation; }
  bool affine() const { return cartesian() || affine_deformation; }
  long n_cells() const {
    long n = 1;
    for (int d = 0; d < dim; ++d) n *= cells[d];
    return n;
  }
  /// Bit 2d + side set where face (d, side) is shared with another rank's box.
  int interface_faces() const {
    int m = 0;
    for (int f = 0; f < 2 * dim; ++f)
      if (faces[f] == FaceCondition::interface) m |= 1 << f;
    return m;
  }
  /// Bit 2d + side set where face (d, side) is Dirichlet.
  int dirichlet_faces() const {
    int m = 0;
    for (int f = 0; f < 2 * dim; ++f)
      if (faces[f] == FaceCondition::dirichlet) m |= 1 << f;
    return m;
  }
  /// Throws std::invalid_argument naming the offending entry (also periodic faces that a
  /// deformation moves apart).
  void validate() const;
  /// The same box with every cell split in two along each direction.
  StructuredHexMesh refined() const;
  /// With half the cells per direction; throws if a count is odd.
  StructuredHexMesh coarsened() const;

 private:
  void check_periodic_match(int d) const;
};

/// The box [0,1]^dim with `n` cells per direction and the given condition on every face.
template <int dim>
StructuredHexMesh<dim> unit_cube(int n, FaceCondition all_faces = FaceCondition::dirichlet);

/// A smooth, non-affine deformation of [0,1]^dim that keeps the box's faces in place
/// (x_d += a sin(pi x_0) sin(pi x_1) [sin(pi x_2)] per direction with a phase), curving the cells.
std::function<Point3(const Point3&)> sinusoidal_deformation(int dim, double amplitude);
/// The same deformation carried to the box [lower, upper] (its faces stay in place, so
/// periodic faces still match).
std::function<Point3(const Point3&)> sinusoidal_deformation(int dim, double amplitude,
                                                            const Point3& lower,
                                                            const Point3& upper);

}  // namespace amphora::mesh::hex
