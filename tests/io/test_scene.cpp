// Scene validation: every kind of bad input gets an error naming file, line, key and what is
// allowed.
#include <filesystem>
#include <fstream>

#include "io/scene.hpp"
#include "io/module_registry.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace {

std::string write_scene(const std::string& name, const std::string& text) {
  const std::string path = "test_scene_" + name + ".toml";
  std::ofstream(path) << text;
  return path;
}

const char* kGood = R"([run]
module = "advection_diffusion_1d"
end_time = 0.5

[advection_diffusion_1d]
cells = 40
nu = 0.1
)";

/// The SceneError message for a scene text (fails the test if it loads).
std::string error_of(const std::string& name, const std::string& text) {
  const std::string path = write_scene(name, text);
  try {
    io::load_scene(path);
  } catch (const io::SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "scene " << name << " loaded but should not";
  return {};
}

void expect_contains(const std::string& s, const std::string& part) {
  EXPECT_NE(s.find(part), std::string::npos) << "'" << part << "' not in: " << s;
}

TEST(Scene, GoodSceneLoadsWithDefaults) {
  const io::Scene s = io::load_scene(write_scene("good", kGood));
  EXPECT_EQ(s.name, "test_scene_good");
  EXPECT_EQ(s.module, "advection_diffusion_1d");
  EXPECT_EQ(s.run.real("end_time"), 0.5);
  EXPECT_EQ(s.run.string("output_dir"), "output");
  EXPECT_FALSE(s.run.has("dt"));
  EXPECT_EQ(s.module_parameters.integer("cells"), 40);
  EXPECT_EQ(s.module_parameters.real("a"), 1.0);  // default
}

TEST(Scene, FingerprintFollowsPhysicsNotRunControl) {
  const io::Scene a = io::load_scene(write_scene("fp", kGood));
  const io::Scene b = io::load_scene(write_scene("fp", kGood), {"run.end_time=2.0"});
  const io::Scene c = io::load_scene(write_scene("fp", kGood), {"advection_diffusion_1d.cells=80"});
  EXPECT_EQ(a.fingerprint, b.fingerprint);
  EXPECT_NE(a.fingerprint, c.fingerprint);
  EXPECT_EQ(c.module_parameters.integer("cells"), 80);
}

TEST(Scene, MissingFile) {
  try {
    io::load_scene("no_such_scene.toml");
    FAIL();
  } catch (const io::SceneError& e) {
    expect_contains(e.what(), "no_such_scene.toml: scene file not found");
  }
}

TEST(Scene, SyntaxErrorNamesFileAndLine) {
  const auto m = error_of("syntax", "[run]\nmodule = \"advection_diffusion_1d\"\nend_time = = 1\n");
  expect_contains(m, "test_scene_syntax.toml:3:");
  expect_contains(m, "TOML syntax error");
}

TEST(Scene, UnknownModule) {
  const auto m = error_of("module", "[run]\nmodule = \"navier_stokes_99\"\nend_time = 1.0\n");
  expect_contains(m, "test_scene_module.toml:2:");
  expect_contains(m, "run.module");
  expect_contains(m, "one of: advection_diffusion_1d");
}

TEST(Scene, UnknownKeyListsValidKeys) {
  const auto m = error_of("key", std::string(kGood) + "viscosity = 3.0\n");
  expect_contains(m, "test_scene_key.toml:8:");
  expect_contains(m, "unknown key 'advection_diffusion_1d.viscosity'");
  expect_contains(m, "valid keys in [advection_diffusion_1d]: a, nu, cells");
}

TEST(Scene, UnknownTableAndTableOfAnotherModule) {
  auto m = error_of("table", std::string(kGood) + "[fluid]\nrho = 1.0\n");
  expect_contains(m, "test_scene_table.toml:8:");
  expect_contains(m, "unknown table [fluid]");
  expect_contains(m, "allowed tables: [run], [advection_diffusion_1d]");
}

TEST(Scene, WrongType) {
  auto m = error_of("type", "[run]\nmodule = \"advection_diffusion_1d\"\nend_time = \"long\"\n");
  expect_contains(m, "test_scene_type.toml:3:");
  expect_contains(m, "run.end_time");
  expect_contains(m, "must be a real number > 0");
  expect_contains(m, "got a string");
  m = error_of("type2",
               "[run]\nmodule = \"advection_diffusion_1d\"\nend_time = 1.0\n"
               "[advection_diffusion_1d]\ncells = 40.5\n");
  expect_contains(m, "test_scene_type2.toml:5:");
  expect_contains(m, "must be an integer");
}

TEST(Scene, NonPositiveResolutionTimeStepAndEndTime) {
  auto m = error_of("res",
                    "[run]\nmodule = \"advection_diffusion_1d\"\nend_time = 1.0\n"
                    "[advection_diffusion_1d]\ncells = -3\n");
  expect_contains(m, "test_scene_res.toml:5:");
  expect_contains(m, "'advection_diffusion_1d.cells' = -3 is out of range");
  expect_contains(m, "allowed: an integer in [8, ");
  m = error_of("dt", "[run]\nmodule = \"advection_diffusion_1d\"\nend_time = 1.0\ndt = 0.0\n");
  expect_contains(m, "test_scene_dt.toml:4:");
  expect_contains(m, "'run.dt' = 0 is out of range; allowed: a real number > 0");
  m = error_of("end", "[run]\nmodule = \"advection_diffusion_1d\"\nend_time = -1\n");
  expect_contains(m, "'run.end_time' = -1 is out of range");
}

TEST(Scene, MissingRequiredKey) {
  const auto m = error_of("req", "[run]\nmodule = \"advection_diffusion_1d\"\n");
  expect_contains(m, "lacks the required key 'end_time'");
}

TEST(Scene, DefaultsAreThemselvesAValidScene) {
  // `amphora defaults` output, with the required keys filled in, loads unchanged.
  std::string text = io::describe_defaults(io::run_parameter_table()) +
                     io::describe_defaults(io::find_module("advection_diffusion_1d")->parameters());
  text.insert(text.find("[run]\n") + 6, "module = \"advection_diffusion_1d\"\nend_time = 1.0\n");
  const io::Scene s = io::load_scene(write_scene("defaults", text));
  EXPECT_EQ(s.module_parameters.real("nu"), 0.05);
}

}  // namespace
}  // namespace amphora
