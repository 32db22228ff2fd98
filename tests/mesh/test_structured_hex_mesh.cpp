#include <cmath>
#include <stdexcept>
#include <string>

#include "mesh/hex/structured_hex_mesh.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace {

using mesh::hex::FaceCondition;
using mesh::hex::Point3;

std::string validate_message(const mesh::hex::StructuredHexMesh<3>& m) {
  try {
    m.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(StructuredHexMesh, PeriodicFacesComeInPairs) {
  auto m = mesh::hex::unit_cube<3>(4, FaceCondition::periodic);
  EXPECT_EQ(validate_message(m), "");
  m.faces[3] = FaceCondition::dirichlet;
  EXPECT_NE(validate_message(m).find("direction 1 is periodic on one face only"),
            std::string::npos);
}

TEST(StructuredHexMesh, DeformedPeriodicFacesMustMatch) {
  auto m = mesh::hex::unit_cube<3>(4, FaceCondition::periodic);
  // A shear keeps every periodic pair a translation apart: accepted.
  m.deformation = [](const Point3& x) { return Point3{x[0] + 0.3 * x[1], x[1], x[2]}; };
  EXPECT_EQ(validate_message(m), "");
  // The sinusoidal map keeps the faces in place and moves their interiors alike: accepted.
  m.deformation = mesh::hex::sinusoidal_deformation(3, 0.05);
  EXPECT_EQ(validate_message(m), "");
  // Stretching x by a factor that depends on y moves the x = 1 face unevenly: refused.
  m.deformation = [](const Point3& x) { return Point3{x[0] * (1.0 + 0.1 * x[1]), x[1], x[2]}; };
  const std::string what = validate_message(m);
  EXPECT_NE(what.find("periodic faces of direction 0 do not match"), std::string::npos) << what;
  // The same map with walls in x and y (it also moves the y = 1 face unevenly) is a valid box.
  for (int f = 0; f < 4; ++f) m.faces[f] = FaceCondition::dirichlet;
  EXPECT_EQ(validate_message(m), "");
}

}  // namespace
}  // namespace amphora
