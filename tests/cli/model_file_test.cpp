// Model-file scenes through the command line: simulate, poincare, sweep,
// periodic and continue run them with no rebuild; the first run compiles
// into the cache and later runs load it; a bad model file exits 2 with one
// FILE:LINE:COL line; a broken compiler says it falls back to the slow path;
// two sweeps started at once on the same new model both succeed (the cache's
// atomic rename).
#include <filesystem>
#include <fstream>
#include <future>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab::testing;

const std::string examples = std::string(IMPACTLAB_SOURCE_DIR) + "/oscillators/model_file/examples/";

// Runs the program with a model cache of its own (`cache`, created) and
// `environment` (NAME=VALUE) added.
ProgramRun run_with_cache(const std::string& arguments, const fs::path& cache,
                          const std::vector<std::string>& environment = {}) {
  fs::create_directories(cache);
  std::vector<std::string> variables = {"IMPACTLAB_CACHE_DIR=" + cache.string()};
  variables.insert(variables.end(), environment.begin(), environment.end());
  return run_command_line(arguments, {.environment = variables});
}

TEST(ModelFileCli, EveryCommandRunsAModelFileAndTheCacheIsReused) {
  const ScratchFolder scratch;
  const fs::path cache = scratch / "cache";
  const fs::path out = scratch / "out";
  const std::string scene = examples + "linear_impact_model.toml";
  const ProgramRun first = run_with_cache(
      "simulate " + scene + " --periods 20 --quiet --out " + (out / "a").string(), cache);
  ASSERT_EQ(first.status, 0) << first.err;
  int shared_objects = 0;
  for (const auto& entry : fs::directory_iterator(cache)) shared_objects += entry.path().extension() == ".so";
  EXPECT_EQ(shared_objects, 1);
  EXPECT_TRUE(fs::exists(out / "a" / "meta.json"));
  EXPECT_NE(slurp(out / "a" / "events.csv").find("impact"), std::string::npos);
  // a second run and the other commands load the same shared object
  for (const std::string& command :
       {"simulate " + scene + " --periods 5 --set r=0.5 --quiet --out " + (out / "b").string(),
        "poincare " + scene + " --section impact --transient 10 --points 5 --quiet --out " + (out / "c").string(),
        "periodic " + scene + " --period 1 --quiet --out " + (out / "d").string(),
        "continue " + scene + " --param omega=2:2.5 --quiet --out " + (out / "e").string()}) {
    const ProgramRun outcome = run_with_cache(command, cache);
    EXPECT_EQ(outcome.status, 0) << command << ": " << outcome.err;
  }
  shared_objects = 0;
  for (const auto& entry : fs::directory_iterator(cache)) shared_objects += entry.path().extension() == ".so";
  EXPECT_EQ(shared_objects, 1);
  // continue: the branch's period doubling and grazing (their closed forms are
  // checked in tests/analysis/continuation_test.cpp)
  const std::string points = slurp(out / "e" / "points.csv");
  EXPECT_NE(points.find("period_doubling,2.265"), std::string::npos) << points;
  EXPECT_NE(points.find("grazing,2.44"), std::string::npos) << points;
}

TEST(ModelFileCli, ABadModelFileExitsTwoWithOneLine) {
  const ScratchFolder scratch;
  const fs::path file = scratch / "bad.toml";
  std::ofstream(file) << "[model]\nstates = [\"x\", \"v\"]\nforcing_frequency = \"1\"\n"
                         "[model.rhs]\nx = \"v\"\nv = \"-x + y\"\n";
  const ProgramRun outcome =
      run_with_cache("simulate " + file.string() + " --quiet", scratch / "cache");
  // the place in the file is the message's subject
  EXPECT_TRUE(refused_naming(outcome, file.string() + ":6:11"));
  EXPECT_EQ(outcome.err.find(file.string() + ":6:11: unknown symbol 'y'"), 11u) << outcome.err;
}

TEST(ModelFileCli, ABrokenCompilerFallsBackToTheSlowPathAndSaysSo) {
  const ScratchFolder scratch;
  const ProgramRun outcome = run_with_cache(
      "simulate " + examples + "bouncing_ball_model.toml --periods 5 --quiet --out " +
          (scratch / "out").string(),
      scratch / "cache", {"IMPACTLAB_CC=/nonexistent/cc"});
  EXPECT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_NE(outcome.err.find("compiler"), std::string::npos) << outcome.err;
  EXPECT_NE(outcome.err.find("slow path"), std::string::npos) << outcome.err;
}

TEST(ModelFileCli, TwoSweepsStartedAtOnceOnANewModelBothSucceed) {
  const ScratchFolder scratch;
  const fs::path cache = scratch / "cache";
  auto sweep = [&](const std::string& label) {
    return run_with_cache("sweep " + examples +
                              "duffing_stop.toml --param omega=1.2:1.6:4 --transient 5 --points 3 "
                              "--quiet --out " + (scratch / label).string(),
                          cache);
  };
  auto first = std::async(std::launch::async, sweep, "sweep1");
  auto second = std::async(std::launch::async, sweep, "sweep2");
  const ProgramRun a = first.get();
  const ProgramRun b = second.get();
  EXPECT_EQ(a.status, 0) << a.err;
  EXPECT_EQ(b.status, 0) << b.err;
  // one object and its digest, no temporary file left
  int shared_objects = 0, digests = 0, leftovers = 0;
  for (const auto& entry : fs::directory_iterator(cache)) {
    const std::string extension = entry.path().extension().string();
    shared_objects += extension == ".so";
    digests += extension == ".sha256";
    leftovers += extension != ".so" && extension != ".sha256";
  }
  EXPECT_EQ(shared_objects, 1);
  EXPECT_EQ(digests, 1);
  EXPECT_EQ(leftovers, 0);
}

// The same 2D classification map (period, impacts per period, contact,
// termination at every grid point) from the built-in linear impact oscillator
// and from its model file, both under the model file's stepper (dopri5 at the
// scene's tolerances: the built-in's default is its exact flow). The map
// crosses the period-doubling and grazing points and the sticking range.
TEST(ModelFileCli, LinearImpactModelFileGivesTheBuiltInSweepClassification) {
  const ScratchFolder scratch;
  const fs::path cache = scratch / "cache";
  const fs::path out = scratch / "out";
  const std::string grid =
      " --param omega=1.6:2.8:7 --param sigma=0:0.3:5 --no-lyapunov --transient 100 "
      "--points 64 --quiet --out ";
  const ProgramRun built_in = run_with_cache(
      "sweep linear_impact --set integrator.method=dopri5" + grid + (out / "built_in").string(),
      cache);
  ASSERT_EQ(built_in.status, 0) << built_in.err;
  const ProgramRun model = run_with_cache(
      "sweep " + examples + "linear_impact_model.toml" + grid + (out / "model").string(), cache);
  ASSERT_EQ(model.status, 0) << model.err;
  const auto expected = split_lines(slurp(out / "built_in" / "classes.csv"));
  const auto actual = split_lines(slurp(out / "model" / "classes.csv"));
  ASSERT_EQ(expected.size(), 7u * 5u + 1u);
  ASSERT_EQ(actual.size(), expected.size());
  // omega,sigma,period,impacts_per_period,contact,lyapunov,termination,stick_fraction,
  // transient_periods,transient_end (an explicit transient: fixed)
  // compared as text: the grid, the period and the termination everywhere;
  // impacts per period and contact where an orbit of some period was found
  // (period 0: no period up to max_period, a chaotic or long transient
  // record whose averages depend on the last bits: the two runs agree to
  // 1e-12 per event, not to all bits, and chaos separates them)
  std::set<std::string> classes;
  int periodic = 0;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    auto fields = [](const std::string& line) {
      std::vector<std::string> out;
      std::stringstream in(line);
      for (std::string field; std::getline(in, field, ',');) out.push_back(field);
      return out;
    };
    const auto e = fields(expected[k]), a = fields(actual[k]);
    ASSERT_EQ(e.size(), 10u) << expected[k];
    ASSERT_EQ(a.size(), 10u) << actual[k];
    const bool has_period = k == 0 || e[2] != "0";
    for (std::size_t column : {0u, 1u, 2u, 3u, 4u, 6u})
      if (has_period || column == 0u || column == 1u || column == 2u || column == 6u) {
        EXPECT_EQ(e[column], a[column]) << "row " << k << ": " << expected[k] << " | " << actual[k];
      }
    if (k > 0 && has_period) {
      ++periodic;
      classes.insert(e[2] + "/" + e[3] + "/" + e[4]);
    }
  }
  // most of the map is periodic, in several classes: the comparison can tell
  // them apart
  EXPECT_GE(periodic, 25);
  EXPECT_GE(classes.size(), 4u);
}

// The Taylor stepper on a model file (its series programs,
// oscillators/model_file/series_program.hpp): a 2D map in the lanes of a
// batch writes the files of the scalar runs, byte for byte, and meta.json
// says how many lanes ran; a model with an operation that has no series is
// refused with exit 2, naming the key and the operation.
TEST(ModelFileCli, TaylorRunsAModelFileInLanesAndRefusesOneWithoutSeries) {
  const ScratchFolder scratch;
  const fs::path cache = scratch / "cache";
  const std::string map = "sweep " + examples +
                          "linear_impact_model.toml --set integrator.method=taylor "
                          "--param omega=1.6:2.8:4 --param sigma=0:0.3:3 --transient 20 "
                          "--points 16 --quiet --out ";
  for (const std::string batch : {"on", "off"}) {
    const ProgramRun run = run_with_cache(map + (scratch / batch).string() + " --batch " + batch, cache);
    ASSERT_EQ(run.status, 0) << run.err;
  }
  // with each point's largest Lyapunov exponent: the variational equations'
  // series in lanes too
  EXPECT_EQ(slurp(scratch / "on" / "classes.csv"), slurp(scratch / "off" / "classes.csv"));
  EXPECT_EQ(split_lines(slurp(scratch / "on" / "classes.csv")).size(), 4u * 3u + 1u);
  const auto width = [&](const std::string& batch) {
    return nlohmann::json::parse(slurp(scratch / batch / "meta.json"))["run"]["batch_width"].get<int>();
  };
  EXPECT_GT(width("on"), 1);
  EXPECT_EQ(width("off"), 1);

  const fs::path file = scratch / "arctangent.toml";
  std::ofstream(file) << "[model]\nstates = [\"x\", \"v\"]\nforcing_frequency = \"1\"\n"
                         "[model.rhs]\nx = \"v\"\nv = \"-atan(x) + cos(t)\"\n";
  const ProgramRun refused = run_with_cache(
      "simulate " + file.string() + " --set integrator.method=taylor --quiet --out " +
          (scratch / "refused").string(),
      cache);
  EXPECT_TRUE(refused_naming(refused, "integrator.method"));
  EXPECT_NE(refused.err.find("uses atan"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(scratch / "refused" / "events.csv"));
}

}  // namespace
