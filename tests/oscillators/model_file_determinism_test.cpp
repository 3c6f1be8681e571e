// A model's generated C source is a function of the model text alone
// (oscillators/model_file/kernel_code.hpp): the same in every process and
// whatever else the process built first, so that the cache key, the compiled
// numbers and every output file are the same too. GiNaC's own printer ordered
// the terms of a sum by addresses: six processes compiling one model wrote up
// to six sources, whose events differed at round-off.
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/oscillators/model_file/compiled_model.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab;
using impactlab::testing::ScratchFolder;
using impactlab::testing::run_impactlab;
using impactlab::testing::slurp;

std::string example(const std::string& name) {
  return std::string(IMPACTLAB_SOURCE_DIR) + "/oscillators/model_file/examples/" + name;
}

std::string source_of(const std::string& file) {
  CompileOptions options;
  options.use_compiler = false;
  return compile_model(read_model_file(file), options)->c_source;
}

TEST(ModelFileDeterminism, OneProcessWritesOneSourcePerModelWhateverItBuiltBefore) {
  for (const std::string name : {"duffing_stop.toml", "impact_damper.toml", "bouncing_ball_model.toml",
                                 "linear_impact_model.toml"}) {
    const std::string first = source_of(example(name));
    for (const std::string other : {"impact_damper.toml", "duffing_stop.toml"}) source_of(example(other));
    EXPECT_EQ(source_of(example(name)), first) << name;
    EXPECT_NE(first.find("impactlab_kernel_0"), std::string::npos) << name;
  }
}

// Six programs per shipped model, each with a cache of its own, write one
// object name (the SHA-256 of the source and the compiler command), and
// byte-identical events.
TEST(ModelFileDeterminism, SixProcessesCompileOneSource) {
  const ScratchFolder scratch;
  for (const std::string name : {"duffing_stop.toml", "impact_damper.toml", "bouncing_ball_model.toml",
                                 "linear_impact_model.toml"}) {
    std::set<std::string> object_names, event_files;
    for (int run = 0; run < 6; ++run) {
      const fs::path cache = scratch / (name + "-cache" + std::to_string(run));
      const fs::path out = scratch / (name + "-out" + std::to_string(run));
      const auto program = run_impactlab(
          {"simulate", example(name), "--periods", "20", "--quiet", "--out", out.string()},
          {.environment = {"IMPACTLAB_CACHE_DIR=" + cache.string()}});
      ASSERT_EQ(program.status, 0) << name << ": " << program.err;
      for (const auto& entry : fs::directory_iterator(cache))
        if (entry.path().extension() == ".so") object_names.insert(entry.path().filename().string());
      event_files.insert(slurp(out / "events.csv"));
    }
    EXPECT_EQ(object_names.size(), 1u) << name;
    ASSERT_EQ(event_files.size(), 1u) << name;
    EXPECT_GT(impactlab::testing::count_lines(*event_files.begin()), 5) << name;
  }
}

}  // namespace
