// Which keys a scene's model reads (api/model_keys.hpp): every schema's
// declaration names models its selector offers; the pendulum's three models
// read exactly the keys their code reads; a sweep, a basin map or a
// continuation over a key the model does not read is refused naming the
// option, and setting one gives one warning per key. The command line's side
// is tests/cli/model_keys_test.cpp, Python's tests/python/test_model_keys.py.
#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/api/basins_job.hpp>
#include <impactlab/api/model_keys.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/sweep_job.hpp>
#include <impactlab/io/bad_input.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::KeySpec;
using impactlab::Scene;
using impactlab::SceneSchema;
using impactlab::testing::bad_input_key;

Scene jin2003_with_model(const std::string& model) {
  Scene scene = impactlab::load_scene("jin2003");
  impactlab::apply_override(scene, "model=" + model);
  return scene;
}

// The message of the BadInput that `action` throws; empty when it throws none.
template <class Action>
std::string bad_input_message(Action&& action) {
  try {
    action();
  } catch (const impactlab::BadInput& bad) {
    return bad.what();
  }
  return "";
}

// A misspelt model in a read_by list (rigd) would make its key unread by every
// model and refuse every sweep of it.
TEST(ModelKeys, EveryDeclaredReaderIsAChoiceOfTheSelector) {
  int schemas_with_selector = 0;
  for (const auto& entry : impactlab::oscillators()) {
    const SceneSchema& schema = *entry.schema;
    SCOPED_TRACE(std::string(schema.oscillator));
    if (schema.selector.empty()) {
      for (const KeySpec& spec : schema.keys) EXPECT_TRUE(spec.read_by.empty()) << spec.key;
      continue;
    }
    ++schemas_with_selector;
    const auto selector = std::find_if(schema.keys.begin(), schema.keys.end(),
                                       [&](const KeySpec& k) { return k.key == schema.selector; });
    ASSERT_NE(selector, schema.keys.end());
    ASSERT_TRUE(selector->is_text);
    EXPECT_TRUE(selector->read_by.empty()) << "every model reads the key that picks it";
    for (const KeySpec& spec : schema.keys)
      for (std::string_view model : spec.read_by)
        EXPECT_NE(std::find(selector->choices.begin(), selector->choices.end(), model),
                  selector->choices.end())
            << spec.key << " read by " << model;
  }
  EXPECT_GE(schemas_with_selector, 1) << "the pendulum declares its model keys";
}

// From the code: PendulumWalls and PaperPendulumWalls read μ (the impulse's
// split, the contact's normal force, the friction work, the Painlevé test),
// the paper's sliding-impact test and the rigid model's stick impulse read
// e_t, and only RigidPendulumBinding::make_system reads radius and spin.
TEST(ModelKeys, Jin2003ModelsReadTheKeysTheirCodeReads) {
  const std::map<std::string, std::vector<std::string>> unread = {
      {"newton", {"e_t", "radius", "spin"}},
      {"paper", {"radius", "spin"}},
      {"rigid", {}},
  };
  const SceneSchema& schema = impactlab::scene_schema(impactlab::load_scene("jin2003"));
  for (const auto& [model, keys] : unread) {
    const Scene scene = jin2003_with_model(model);
    for (const KeySpec& spec : schema.keys) {
      const std::string key(spec.key);
      const bool expected_unread = std::find(keys.begin(), keys.end(), key) != keys.end();
      EXPECT_EQ(!impactlab::unread_key_reason(scene, schema, key).empty(), expected_unread)
          << "model = " << model << ", key " << key;
    }
  }
  EXPECT_EQ(impactlab::unread_key_reason(jin2003_with_model("newton"), schema, "e_t"),
            "model = newton does not read e_t (read by model = paper|rigid)");
  EXPECT_EQ(impactlab::unread_key_reason(jin2003_with_model("paper"), schema, "spin"),
            "model = paper does not read spin (read by model = rigid)");
}

TEST(ModelKeys, ASchemaWithoutSelectorReadsEveryKey) {
  const Scene scene = impactlab::load_scene("linear_impact");
  const SceneSchema& schema = impactlab::scene_schema(scene);
  ASSERT_TRUE(schema.selector.empty());
  for (const KeySpec& spec : schema.keys) {
    EXPECT_EQ(impactlab::unread_key_reason(scene, schema, spec.key), "") << spec.key;
    EXPECT_TRUE(impactlab::models_reading(schema, spec).empty()) << spec.key;
  }
}

TEST(ModelKeys, ModelsReadingListsTheDeclaredModelsOrEveryChoice) {
  const SceneSchema& schema = impactlab::scene_schema(impactlab::load_scene("jin2003"));
  const auto listed = [&](std::string_view key) {
    const auto spec = std::find_if(schema.keys.begin(), schema.keys.end(),
                                   [&](const KeySpec& k) { return k.key == key; });
    return impactlab::model_names(impactlab::models_reading(schema, *spec));
  };
  EXPECT_EQ(listed("e_t"), "paper|rigid");
  EXPECT_EQ(listed("radius"), "rigid");
  EXPECT_EQ(listed("mu"), "newton|paper|rigid");
}

TEST(ModelKeys, SweepOfAKeyTheModelDoesNotReadIsRefusedNamingParam) {
  const Scene newton = jin2003_with_model("newton");
  const SceneSchema& schema = impactlab::scene_schema(newton);
  impactlab::SweepSpec spec;
  spec.params = {"e_t=-0.5:0:3"};
  EXPECT_EQ(bad_input_key([&] { impactlab::make_sweep_plan(spec, newton, schema); }), "param");
  EXPECT_EQ(bad_input_message([&] { impactlab::make_sweep_plan(spec, newton, schema); }),
            "param = e_t: model = newton does not read e_t (read by model = paper|rigid)");
  // the second axis of a map too
  spec.params = {"omega=6:7:2", "radius=0:0.01:2"};
  EXPECT_EQ(bad_input_key([&] { impactlab::make_sweep_plan(spec, newton, schema); }), "param");
  // Model P reads e_t: the same sweep is planned
  spec.params = {"e_t=-0.5:0:3"};
  EXPECT_EQ(bad_input_key([&] {
              impactlab::make_sweep_plan(spec, jin2003_with_model("paper"), schema);
            }),
            "(no BadInput)");
  // μ is read by Model N
  spec.params = {"mu=0:3:150"};
  EXPECT_EQ(bad_input_key([&] { impactlab::make_sweep_plan(spec, newton, schema); }),
            "(no BadInput)");
}

TEST(ModelKeys, BasinsOverAKeyTheModelDoesNotReadAreRefusedNamingTheAxis) {
  const Scene newton = jin2003_with_model("newton");
  const SceneSchema& schema = impactlab::scene_schema(newton);
  impactlab::BasinsSpec spec;
  spec.x = "initial.theta=-0.05:0.05:3";
  spec.y = "e_t=-0.5:0:3";
  EXPECT_EQ(bad_input_key([&] { impactlab::make_basins_plan(spec, newton, schema); }), "y");
  std::swap(spec.x, spec.y);
  EXPECT_EQ(bad_input_key([&] { impactlab::make_basins_plan(spec, newton, schema); }), "x");
  EXPECT_EQ(bad_input_key([&] {
              impactlab::make_basins_plan(spec, jin2003_with_model("paper"), schema);
            }),
            "(no BadInput)");
}

TEST(ModelKeys, ContinuationOfAKeyTheModelDoesNotReadIsRefusedNamingTheOption) {
  const Scene newton = jin2003_with_model("newton");
  impactlab::ContinuationJob job;
  job.parameter = "e_t";
  job.from = -0.5;
  job.to = 0.0;
  EXPECT_EQ(bad_input_key([&] { impactlab::continue_orbit(newton, job); }), "param");
  job.parameter = "omega";
  job.from = 6.0;
  job.to = 7.0;
  job.second_parameter = "radius";
  job.second_from = 0.0;
  job.second_to = 0.01;
  EXPECT_EQ(bad_input_key([&] { impactlab::continue_orbit(newton, job); }), "param2");
  EXPECT_EQ(bad_input_message([&] { impactlab::continue_orbit(newton, job); }),
            "param2 = radius: model = newton does not read radius (read by model = rigid)");
}

TEST(ModelKeys, SettingAKeyTheModelDoesNotReadWarnsOncePerKey) {
  Scene newton = jin2003_with_model("newton");
  impactlab::apply_override(newton, "e_t=-0.2");
  const SceneSchema& schema = impactlab::scene_schema(newton);
  const std::vector<std::string> warnings =
      impactlab::unread_key_warnings(newton, schema, {"e_t", "mu", "e_t", "V0"});
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "e_t = -0.2: model = newton does not read e_t (read by model = paper|rigid); the value "
            "changes nothing");
  EXPECT_EQ(impactlab::unread_key_warnings(jin2003_with_model("paper"), schema, {"e_t", "mu"}),
            std::vector<std::string>{});
}

}  // namespace
