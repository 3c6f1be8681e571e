// A scene written back as a scene file (src/io/scene_file.hpp) loads as the
// same scene: every built-in scene with keys set to values that need every
// digit, a scene of a model file (its [model] section kept), and a file that
// cannot be written leaves nothing behind.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include <impactlab/api/scene_loading.hpp>
#include <impactlab/io/builtin_scenes.hpp>
#include <impactlab/io/output_error.hpp>
#include <impactlab/io/scene_file.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::testing::ScratchFolder;

// the scene saved and loaded again has the same value at every key, bit for bit
void expect_round_trip(const impactlab::Scene& scene, const std::filesystem::path& file) {
  impactlab::save_scene_file(scene, impactlab::scene_schema(scene), file);
  const impactlab::Scene loaded = impactlab::load_scene(file.string());
  EXPECT_EQ(loaded.oscillator, scene.oscillator);
  EXPECT_EQ(loaded.values, scene.values) << impactlab::scene_file_text(
      scene, impactlab::scene_schema(scene));
}

TEST(SceneFile, EveryBuiltInSceneLoadsBackAsItWas) {
  const ScratchFolder scratch;
  for (const auto& builtin : impactlab::builtin_scenes()) {
    SCOPED_TRACE(std::string(builtin.name));
    impactlab::Scene scene = impactlab::load_scene(builtin.name);
    expect_round_trip(scene, scratch / (std::string(builtin.name) + ".toml"));
    // a start time and a tolerance whose shortest decimal texts are long
    impactlab::apply_override(scene, "t0=0.30000000000000004");
    impactlab::apply_override(scene, "integrator.rtol=1.2345678901234567e-11");
    expect_round_trip(scene, scratch / (std::string(builtin.name) + "_set.toml"));
  }
  impactlab::Scene rigid = impactlab::load_scene("jin2003");
  for (const char* assignment : {"model=rigid", "spin=free", "radius=0.02", "omega=6.71"})
    impactlab::apply_override(rigid, assignment);
  expect_round_trip(rigid, scratch / "rigid.toml");
}

TEST(SceneFile, AModelFilesSceneKeepsItsModel) {
  const ScratchFolder scratch;
  impactlab::Scene scene = impactlab::load_scene(
      std::string(IMPACTLAB_SOURCE_DIR) + "/oscillators/model_file/examples/duffing_stop.toml");
  impactlab::apply_override(scene, "r=0.35");
  const auto file = scratch / "duffing.toml";
  impactlab::save_scene_file(scene, impactlab::scene_schema(scene), file);
  const impactlab::Scene loaded = impactlab::load_scene(file.string());
  // the saved file defines the same model (its own oscillator, named by its path)
  EXPECT_EQ(loaded.oscillator, impactlab::model_oscillator_name(file.string()));
  EXPECT_EQ(loaded.values, scene.values);
}

TEST(SceneFile, AFileThatCannotBeWrittenLeavesNothing) {
  const ScratchFolder scratch;
  const impactlab::Scene scene = impactlab::load_scene("jin2003");
  const auto file = scratch / "missing_folder" / "scene.toml";
  EXPECT_THROW(impactlab::save_scene_file(scene, impactlab::scene_schema(scene), file),
               impactlab::OutputError);
  EXPECT_FALSE(std::filesystem::exists(scratch / "missing_folder"));
}

}  // namespace
