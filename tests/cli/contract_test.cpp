// The command-line contract (docs/simulation.md, "Robustness"): bad input exits with status 2 and
// one line on stderr naming the key and the value, writes nothing; a good run
// writes complete events.csv and meta.json.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab::testing;

struct BadCase {
  std::string name;        // test name
  std::string arguments;   // "{scene}" stands for a scene file written from scene_text
  std::string key;         // the subject of the message
  std::string value;
  std::string scene_text{};
};

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, ExitsTwoWithOneLineNamingKeyAndValue) {
  const auto& c = GetParam();
  const ScratchFolder scratch;
  std::string arguments = c.arguments;
  if (!c.scene_text.empty()) {
    const auto path = scratch / (c.name + ".toml");
    std::ofstream(path) << c.scene_text;
    arguments.replace(arguments.find("{scene}"), 7, path.string());
  }
  const auto out_dir = scratch / "bad_out";
  const ProgramRun run = run_command_line(arguments + " --out " + out_dir.string());
  EXPECT_TRUE(refused_naming(run, c.key));
  EXPECT_NE(run.err.find(c.value), std::string::npos) << run.err;
  // nothing half-written
  EXPECT_FALSE(std::filesystem::exists(out_dir / "events.csv"));
  EXPECT_FALSE(std::filesystem::exists(out_dir / "meta.json"));
}

INSTANTIATE_TEST_SUITE_P(
    DesignContract, BadInput,
    ::testing::Values(
        BadCase{"unknown_scene", "simulate no_such_scene", "scene", "no_such_scene"},
        BadCase{"unknown_key", "simulate jin2003 --set colour=3", "colour", "3"},
        BadCase{"restitution_above_one", "simulate jin2003 --set e_n=1.5", "e_n", "1.5"},
        BadCase{"restitution_negative", "simulate jin2003 --set e_n=-0.1", "e_n", "-0.1"},
        BadCase{"tangential_restitution_positive", "simulate jin2003 --set e_t=0.5", "e_t", "0.5"},
        BadCase{"friction_negative", "simulate jin2003 --set mu=-1", "mu", "-1"},
        BadCase{"walls_at_rod_length", "simulate jin2003 --set b=0.7", "b", "0.7"},
        BadCase{"walls_beyond_rod", "simulate jin2003 --set b=2", "b", "2"},
        BadCase{"not_a_number", "simulate jin2003 --set omega=nan", "omega", "nan"},
        BadCase{"infinite", "simulate jin2003 --set V0=inf", "V0", "inf"},
        BadCase{"text_for_number", "simulate jin2003 --set V0=fast", "V0", "fast"},
        BadCase{"zero_tolerance", "simulate jin2003 --set integrator.rtol=0", "integrator.rtol", "0"},
        BadCase{"unknown_method", "simulate jin2003 --set integrator.method=euler",
                "integrator.method", "euler"},
        BadCase{"exact_without_flow", "simulate jin2003 --set integrator.method=exact",
                "integrator.method", "exact"},
        BadCase{"start_inside_wall", "simulate jin2003 --set initial.theta=0.2", "initial.theta",
                "0.2"},
        BadCase{"unknown_model", "simulate jin2003 --set model=quantum", "model", "quantum"},
        BadCase{"oscillator_not_settable", "simulate jin2003 --set oscillator=bouncing_ball",
                "oscillator", "bouncing_ball"},
        BadCase{"assignment_without_value", "simulate jin2003 --set omega", "--set", "omega"},
        BadCase{"negative_periods", "simulate jin2003 --periods -5", "--periods", "-5"},
        BadCase{"nan_periods", "simulate jin2003 --periods nan", "--periods", "nan"},
        BadCase{"infinite_end", "simulate jin2003 --t-end inf", "--t-end", "inf"},
        BadCase{"unknown_option", "simulate jin2003 --bogus-option", "--bogus-option", "bogus"},
        BadCase{"malformed_file", "simulate {scene}", "scene", "malformed_file",
                "oscillator = \"pendulum_walls\"\nm = \n"},
        BadCase{"unknown_oscillator", "simulate {scene}", "oscillator", "spring",
                "oscillator = \"spring\"\n"},
        BadCase{"file_value_out_of_range", "simulate {scene}", "l", "-0.7",
                "oscillator = \"pendulum_walls\"\nl = -0.7\n"},
        BadCase{"file_boolean_value", "simulate {scene}", "m", "true",
                "oscillator = \"pendulum_walls\"\nm = true\n"}),
    [](const ::testing::TestParamInfo<BadCase>& info) { return info.param.name; });

TEST(Simulate, WritesCompleteEventsAndMeta) {
  const ScratchFolder scratch;
  const auto out_dir = scratch / "good";
  const ProgramRun run = run_impactlab(
      {"simulate", "jin2003", "--periods", "20", "--quiet", "--sample", "0.01", "--out", out_dir});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(run.out.empty());
  const std::string events = slurp(out_dir / "events.csv");
  ASSERT_EQ(events.rfind("t,kind,wall,q,qdot_before,qdot_after", 0), 0u);
  const auto meta = nlohmann::json::parse(slurp(out_dir / "meta.json"));
  EXPECT_EQ(meta["scene"]["oscillator"], "pendulum_walls");
  EXPECT_EQ(meta["integrator"]["method"], "taylor");
  EXPECT_EQ(meta["run"]["termination"], "completed");
  EXPECT_GT(meta["counts"]["impacts"].get<int>(), 0);
  EXPECT_EQ(meta["scene"]["keys"]["omega"]["unit"], "rad/s");
  // one line per event after the header
  EXPECT_EQ(count_lines(events) - 1, meta["counts"]["events"].get<int>());
  // no temporary left behind
  for (const auto& entry : std::filesystem::directory_iterator(out_dir))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

// events.csv carries the columns its model fills and no others: the core's
// for every model, the bob's impulse, slip, contact force and friction work
// for the pendulum, Model P's residuals, the rigid model's slip after an
// impact; a model file and the bouncing ball, the core's alone. meta.json
// describes the same columns.
TEST(Simulate, EventsCarryOnlyTheColumnsTheirModelFills) {
  const ScratchFolder scratch;
  const std::string core = "t,kind,wall,q,qdot_before,qdot_after,";
  const std::string bob = "normal_impulse,tangential_velocity,normal_force,friction_work,";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"simulate jin2003", core + bob + "accumulation_error"},
      {"simulate jin2003 --set model=paper",
       core + bob + "instantaneous_residual,sliding_residual,accumulation_error"},
      {"simulate jin2003 --set model=rigid", core + bob + "tangential_velocity_after,accumulation_error"},
      {"simulate bouncing_ball", core + "accumulation_error"},
      {"simulate " + std::string(IMPACTLAB_SOURCE_DIR) +
           "/oscillators/model_file/examples/duffing_stop.toml",
       core + "accumulation_error"}};
  for (const auto& [command, header] : cases) {
    SCOPED_TRACE(command);
    const auto out = scratch / "run";
    const ProgramRun run = run_command_line(
        command + " --periods 5 --quiet --out " + out.string(),
        {.environment = {"IMPACTLAB_CACHE_DIR=" + (scratch / "cache").string()}, .limit_s = 120});
    ASSERT_EQ(run.status, 0) << run.err;
    const std::string events = slurp(out / "events.csv");
    EXPECT_EQ(events.substr(0, events.find('\n')), header);
    const auto described = nlohmann::json::parse(slurp(out / "meta.json"))["columns"]["events.csv"];
    EXPECT_EQ(described.size(), static_cast<std::size_t>(std::count(header.begin(), header.end(), ',') + 1));
  }
}

TEST(Simulate, SetOverridesReachTheRun) {
  const ScratchFolder scratch;
  const auto out_dir = scratch / "override";
  const ProgramRun run =
      run_impactlab({"simulate", "jin2003", "--periods", "5", "--quiet", "--set", "omega=6.5",
                     "--set", "integrator.method=rk8pd", "--out", out_dir});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto meta = nlohmann::json::parse(slurp(out_dir / "meta.json"));
  EXPECT_EQ(meta["scene"]["keys"]["omega"]["value"].get<double>(), 6.5);
  EXPECT_EQ(meta["integrator"]["method"], "rk8pd");
  EXPECT_NEAR(meta["run"]["t_end_s"].get<double>(), 5 * 2 * M_PI / 6.5, 1e-12);
}

// meta.json's derived friction work is that of the last contact phase in
// events.csv, although the run streams its events to the file instead of
// keeping them (the tally sees each event as it passes: api/event_tap.hpp).
TEST(Simulate, DerivedFrictionWorkIsTheLastContactPhasesOfTheStreamedEvents) {
  const ScratchFolder scratch;
  const auto out_dir = scratch / "friction";
  const ProgramRun run = run_impactlab(
      {"simulate", "jin2003", "--periods", "30", "--quiet", "--set", "V0=4.163", "--out", out_dir});
  ASSERT_EQ(run.status, 0) << run.err;
  std::stringstream events(slurp(out_dir / "events.csv"));
  std::string last_contact_end;
  for (std::string line; std::getline(events, line);)
    if (line.find(",contact_end,") != std::string::npos) last_contact_end = line;
  ASSERT_FALSE(last_contact_end.empty());
  std::vector<std::string> fields;
  std::stringstream row(last_contact_end);
  for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
  ASSERT_GE(fields.size(), 10u);  // friction_work is the 10th column
  const double friction_work = std::stod(fields[9]);
  EXPECT_GT(friction_work, 0.0);
  const auto meta = nlohmann::json::parse(slurp(out_dir / "meta.json"));
  EXPECT_EQ(meta["derived"]["friction_work_J"].get<double>(), friction_work);
}

// μ tan θ0 = 15 · 0.0716 > 1: the first impact that slips downwards (γ_T > 0)
// is a Painlevé configuration, so the run stops there with exit status 3 and
// complete outputs that say why.
TEST(Simulate, PainleveStopExitsThreeWithCompleteOutputs) {
  const ScratchFolder scratch;
  const auto out_dir = scratch / "painleve";
  const ProgramRun run =
      run_impactlab({"simulate", "jin2003", "--quiet", "--set", "mu=15", "--out", out_dir});
  EXPECT_EQ(run.status, 3) << run.err;
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("painleve"), std::string::npos) << run.err;
  const auto meta = nlohmann::json::parse(slurp(out_dir / "meta.json"));
  EXPECT_EQ(meta["run"]["termination"], "stopped_by_model");
  const std::string events = slurp(out_dir / "events.csv");
  const auto last_line_start = events.rfind('\n', events.size() - 2) + 1;
  const std::string last = events.substr(last_line_start);
  EXPECT_NE(last.find(",painleve,"), std::string::npos) << last;
  // its tangential velocity (8th column) points down the wall
  std::vector<std::string> fields;
  std::stringstream row(last);
  for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
  ASSERT_GE(fields.size(), 8u);
  EXPECT_GT(std::stod(fields[7]), 0.0);
  EXPECT_EQ(meta["run"]["t_final_s"].get<double>(), std::stod(fields[0]));
}

// --direction up follows the parameter's increasing values however the
// range is written: omega=9:5:5 is the same sweep as omega=5:9:5, rows and
// labels alike (it was walked 9 → 5 and labelled up)
TEST(Sweep, UpFollowsIncreasingValuesWhicheverWayTheRangeIsWritten) {
  const ScratchFolder scratch;
  std::string written[2];
  int k = 0;
  for (const char* range : {"omega=5:9:5", "omega=9:5:5"}) {
    const auto out_dir = scratch / ("sweep" + std::to_string(k));
    const ProgramRun run = run_impactlab({"sweep", "jin2003", "--param", range, "--no-lyapunov",
                                          "--direction", "both", "--quiet", "--out", out_dir});
    ASSERT_EQ(run.status, 0) << run.err;
    written[k++] = slurp(out_dir / "summary.csv");
  }
  EXPECT_EQ(written[1], written[0]);
  std::stringstream rows(written[0]);
  std::string header, first;
  std::getline(rows, header);
  std::getline(rows, first);
  EXPECT_EQ(first.rfind("5,up,", 0), 0u) << first;
}

// a stop reason without detail is printed bare, not with empty brackets
TEST(Continue, AStopWithoutDetailHasNoEmptyBrackets) {
  const ScratchFolder scratch;
  const ProgramRun run = run_impactlab({"continue", "linear_impact", "--set", "sigma=0.2", "--param",
                                        "omega=1.5:1.6", "--out", scratch / "branch"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("stopped: end_of_range\n"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("()"), std::string::npos) << run.out;
}

// the model files that ship with the program (every file of the source
// tree's examples folder) are listed by a path the program itself runs,
// beside their description
TEST(Scenes, ListsTheShippedModelFilesByAPathThatRuns) {
  int shipped = 0;
  for (const auto& entry : std::filesystem::directory_iterator(
           std::filesystem::path(IMPACTLAB_SOURCE_DIR) / "oscillators/model_file/examples"))
    if (entry.path().extension() == ".toml") ++shipped;
  const ProgramRun run = run_impactlab({"scenes"});
  ASSERT_EQ(run.status, 0) << run.err;
  std::stringstream lines(run.out);
  std::string line, duffing;
  int listed = 0;
  while (std::getline(lines, line))
    if (line.find(".toml") != std::string::npos) {
      ++listed;
      if (line.find("duffing_stop.toml") != std::string::npos) duffing = line;
    }
  EXPECT_EQ(listed, shipped);
  ASSERT_FALSE(duffing.empty()) << run.out;
  EXPECT_NE(duffing.find("Duffing oscillator against a rigid stop"), std::string::npos);
  const std::size_t start = duffing.find_first_not_of(' ');
  const std::string path = duffing.substr(start, duffing.find(".toml") + 5 - start);
  const ScratchFolder scratch;
  const ProgramRun simulated = run_impactlab(
      {"simulate", path, "--periods", "2", "--quiet", "--out", scratch / "duffing"},
      {.environment = {"IMPACTLAB_CACHE_DIR=" + (scratch / "cache").string()}, .limit_s = 120});
  EXPECT_EQ(simulated.status, 0) << path << ": " << simulated.err;
}

TEST(Scenes, ListsTheDefaultScene) {
  const ProgramRun run = run_impactlab({"scenes"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("jin2003"), std::string::npos);
  const ProgramRun keys = run_impactlab({"scenes", "jin2003"});
  ASSERT_EQ(keys.status, 0) << keys.err;
  EXPECT_NE(keys.out.find("initial.theta_dot"), std::string::npos);
}

TEST(Help, EverySubcommandHasHelp) {
  for (const std::string sub : {"", "simulate ", "scenes "}) {
    const ProgramRun run = run_command_line(sub + "--help");
    EXPECT_EQ(run.status, 0) << sub;
    EXPECT_NE(run.out.find("Usage"), std::string::npos) << sub;
  }
  EXPECT_EQ(run_impactlab({"--version"}).status, 0);
}

}  // namespace
