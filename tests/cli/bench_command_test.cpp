// `impactlab bench --quick`: the files it writes and their structure, and
// that the measured errors fall as the tolerance tightens (speed is not
// tested: it is what the bench reports). The bad-input contract of its
// options is checked here too.
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab::testing;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

class BenchQuick : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = std::make_unique<ScratchFolder>();
    result_ = run_command_line("bench --quick --quiet --out " + (*scratch_ / "out").string());
  }
  static void TearDownTestSuite() { scratch_.reset(); }

  static inline std::unique_ptr<ScratchFolder> scratch_;
  static inline ProgramRun result_;
};

TEST_F(BenchQuick, WritesTheDataItsSidecarAndOnePlotPerCase) {
  ASSERT_EQ(result_.status, 0) << result_.err;
  const fs::path out = *scratch_ / "out";
  std::ifstream meta_file(out / "work_precision.json");
  ASSERT_TRUE(meta_file.good());
  const auto meta = nlohmann::json::parse(meta_file);
  for (const char* key : {"impactlab_version", "command", "created_utc", "cases", "targets",
                          "wall_time_s", "counts", "columns", "scipy"})
    EXPECT_TRUE(meta.contains(key)) << key;
  EXPECT_EQ(meta["quick"], true);
  ASSERT_EQ(meta["cases"].size(), 4u);
  for (const auto& bench_case : meta["cases"]) {
    const std::string name = bench_case["name"];
    EXPECT_TRUE(fs::exists(out / (name + ".png"))) << name;
    EXPECT_GT(bench_case["reference"]["impacts_compared"].get<int>(), 10) << name;
    EXPECT_TRUE(bench_case["scene"].contains("keys")) << name;
  }
  // no temporary left behind
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_NE(entry.path().filename().string().front(), '.') << entry.path();
  // the pendulum's reference: two methods, their spread far below the errors studied
  const auto& pendulum = meta["cases"][0];
  EXPECT_EQ(pendulum["name"], "jin2003_periodic");
  EXPECT_LT(pendulum["reference"]["time_spread"].get<double>(), 1e-10);
  EXPECT_TRUE(meta["targets"].contains("speed_ratio_vs_scipy_pendulum"));
  EXPECT_TRUE(meta["targets"].contains("speed_ratio_vs_scipy_dop853_pendulum"));
  EXPECT_TRUE(meta["targets"].contains("impacts_per_second_at_time_error_1e-9_jin2003"));
}

TEST_F(BenchQuick, ErrorsFallAsTheToleranceTightens) {
  ASSERT_EQ(result_.status, 0) << result_.err;
  std::ifstream csv(*scratch_ / "out" / "work_precision.csv");
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  const auto header = split(line);
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  for (const char* name : {"case", "tool", "method", "rtol", "seconds_per_impact", "rhs_per_impact",
                           "max_time_error", "max_velocity_error", "compared_impacts",
                           "reference_impacts"})
    ASSERT_TRUE(column.count(name)) << name;

  // max time error per (case, tool, method) at each rtol
  std::map<std::string, std::map<double, double>> errors;
  std::set<std::string> tools;
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    const auto f = split(line);
    ASSERT_EQ(f.size(), header.size()) << line;
    ++rows;
    tools.insert(f[column["tool"]]);
    EXPECT_GT(std::stod(f[column["seconds_per_impact"]]), 0.0) << line;
    EXPECT_EQ(f[column["compared_impacts"]], f[column["reference_impacts"]]) << line;
    errors[f[column["case"]] + "/" + f[column["tool"]] + "/" + f[column["method"]]]
          [std::stod(f[column["rtol"]])] = std::stod(f[column["max_time_error"]]);
  }
  EXPECT_GT(rows, 40u);
  EXPECT_TRUE(tools.count("impactlab"));
  EXPECT_TRUE(tools.count("scipy"));

  // where the loosest tolerance leaves an error above the reference's
  // resolution (1e-10), the tightest must reduce it; dopri5 (5th order, not
  // held back by the step bound) by more than tenfold
  std::size_t checked = 0;
  for (const char* bench_case : {"jin2003_periodic", "linear_impact"}) {
    for (const char* method : {"dopri5", "rkf78", "bulirsch_stoer", "rk8pd"}) {
      const auto& by_rtol = errors[std::string(bench_case) + "/impactlab/" + method];
      ASSERT_TRUE(by_rtol.count(1e-6) && by_rtol.count(1e-10)) << bench_case << " " << method;
      const double loose = by_rtol.at(1e-6), tight = by_rtol.at(1e-10);
      if (loose <= 1e-10) continue;
      ++checked;
      EXPECT_LT(tight, loose) << bench_case << " " << method;
      if (std::string(method) == "dopri5") {
        EXPECT_LT(10.0 * tight, loose) << bench_case;
      }
    }
  }
  EXPECT_GE(checked, 3u);
  // the exact flow is exact: round-off only
  EXPECT_LT(errors["linear_impact/impactlab/exact"].at(1e-10), 1e-12);
  EXPECT_LT(errors["bouncing_ball/impactlab/exact"].at(1e-10), 1e-12);
}

// bad options are refused before any work: exit 2, one line naming the option
TEST(BenchBadInput, ExitsTwoWithOneLineNamingTheOption) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--repetitions 0", "--repetitions"},
      {"--python /nonexistent/python", "--python"},
      {"--out /proc/impactlab/bench", "--out"},
  };
  for (const auto& [arguments, option] : cases) {
    const ProgramRun result = run_command_line("bench --quick " + arguments);
    EXPECT_TRUE(refused_naming(result, option)) << arguments;
  }
}

}  // namespace
