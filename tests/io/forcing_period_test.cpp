// A scene's forcing period (src/io/scene.hpp, Scene::forcing_period): 2π/ω
// where the scene has a forcing frequency, and bad input naming the scene
// where it has none.
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/scene.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

TEST(ForcingPeriod, IsTwoPiOverOmega) {
  impactlab::Scene scene;
  scene.name = "forced";
  scene.values["omega"] = 4.0;
  EXPECT_DOUBLE_EQ(scene.forcing_period(), std::numbers::pi / 2.0);
}

TEST(ForcingPeriod, ASceneWithoutOmegaIsRefusedByName) {
  impactlab::Scene scene;
  scene.name = "unforced.toml";
  scene.values["t0"] = 0.0;
  try {
    static_cast<void>(scene.forcing_period());
    FAIL() << "a scene without omega has no forcing period";
  } catch (const impactlab::BadInput& error) {
    EXPECT_EQ(error.key(), "scene");
    EXPECT_EQ(error.value(), "unforced.toml");
    const std::string message = error.what();
    EXPECT_NE(message.find("unforced.toml"), std::string::npos) << message;
    EXPECT_NE(message.find("omega"), std::string::npos) << message;
  }
}

}  // namespace IMPACTLAB_TEST_FILE_SCOPE
