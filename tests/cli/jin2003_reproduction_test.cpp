// Tests of `impactlab reproduce jin2003` (api/jin2003_reproduction.hpp):
// * the ranges in report.json and REPORT.md are re-derived here from the
//   CSVs, by code written in this file (a CSV reader, the residual's formula
//   and the range rule), for a quick run and for the committed report in
//   notebooks_data/jin2003;
// * every residual in the CSVs equals √(V0² − (g/ω)²) + e_y v_y0 computed here;
// * the files do not depend on the thread count;
// * bad input exits 2 with one line naming the key and the value.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab::testing;

// A CSV as rows of named text fields.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::stringstream header(line); std::getline(header, line, ',');) names.push_back(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::map<std::string, std::string> row;
    std::stringstream fields(line);
    std::string field;
    for (const auto& name : names) {
      std::getline(fields, field, ',');
      row[name] = field;
    }
    rows.push_back(row);
  }
  return rows;
}

using Ranges = std::vector<std::pair<double, double>>;

// The rule stated in REPORT.md, written again: grid values where some kept
// impact of the model has |residual| ≤ tolerance, joined when consecutive.
Ranges derive_ranges(const fs::path& directory, const std::string& figure,
                     const std::string& model, double tolerance) {
  const auto meta = nlohmann::json::parse(slurp(directory / (figure + ".json")));
  const auto& grid = meta["grid"];
  const std::string parameter = grid["parameter"];
  const double from = grid["from"], to = grid["to"];
  const int points = grid["points"];
  std::set<long> met;  // grid indices
  for (const auto& row : read_csv(directory / (figure + ".csv"))) {
    if (row.at("model") != model || row.at("sliding_residual").empty()) continue;
    if (std::fabs(std::stod(row.at("sliding_residual"))) > tolerance) continue;
    met.insert(std::lround((std::stod(row.at(parameter)) - from) / (to - from) * (points - 1)));
  }
  Ranges ranges;
  for (long i = 0; i < points; ++i) {
    if (!met.contains(i)) continue;
    const double value = from + (to - from) * static_cast<double>(i) / (points - 1);
    if (!ranges.empty() && met.contains(i - 1))
      ranges.back().second = value;
    else
      ranges.emplace_back(value, value);
  }
  return ranges;
}

std::string format_range(const std::pair<double, double>& r) {
  return r.first == r.second ? fmt::format("{:.3f}", r.first)
                             : fmt::format("{:.3f}–{:.3f}", r.first, r.second);
}

// Every stated range of report.json equals the re-derived one, and REPORT.md
// shows it.
void check_report(const fs::path& directory) {
  const auto report = nlohmann::json::parse(slurp(directory / "report.json"));
  const std::string markdown = slurp(directory / "REPORT.md");
  int compared = 0;
  for (const std::string figure : {"fig4a", "fig4b"}) {
    for (const auto& [model, by_tolerance] : report["ranges"][figure]["toolkit"].items()) {
      for (const auto& [tolerance, stated] : by_tolerance.items()) {
        const Ranges derived = derive_ranges(directory, figure, model, std::stod(tolerance));
        ASSERT_EQ(derived.size(), stated.size()) << figure << ' ' << model << ' ' << tolerance;
        for (std::size_t i = 0; i < derived.size(); ++i) {
          EXPECT_NEAR(derived[i].first, stated[i][0].get<double>(), 1e-9);
          EXPECT_NEAR(derived[i].second, stated[i][1].get<double>(), 1e-9);
          EXPECT_NE(markdown.find(format_range(derived[i])), std::string::npos)
              << format_range(derived[i]) << " missing from REPORT.md";
        }
        ++compared;
      }
    }
  }
  EXPECT_GE(compared, 6);  // two figures, at least one model, three tolerances
}

// The residual of every row, from the velocity in the same row and the scene.
void check_residuals(const fs::path& directory, const std::string& figure) {
  const auto meta = nlohmann::json::parse(slurp(directory / (figure + ".json")));
  const auto& keys = meta["scene"]["keys"];
  const double g = keys["g"]["value"], e_t = keys["e_t"]["value"];
  const std::string parameter = meta["grid"]["parameter"];
  const double fixed = meta["grid"]["fixed"].begin().value();
  int checked = 0;
  for (const auto& row : read_csv(directory / (figure + ".csv"))) {
    const double value = std::stod(row.at(parameter));
    const double V0 = parameter == "V0" ? value : fixed;
    const double omega = parameter == "omega" ? value : fixed;
    const double squared = V0 * V0 - (g / omega) * (g / omega);
    if (squared < 0.0) {
      EXPECT_TRUE(row.at("sliding_residual").empty());
      continue;
    }
    const double expected = std::sqrt(squared) + e_t * std::stod(row.at("tangential_velocity"));
    EXPECT_NEAR(std::stod(row.at("sliding_residual")), expected, 1e-12);
    ++checked;
  }
  EXPECT_GT(checked, 100) << figure;
}

// One test, so that the two quick runs (a few seconds each) happen once.
TEST(QuickReproduction, RangesResidualsSlipsAndThreadIndependence) {
  const ScratchFolder scratch;
  const fs::path one_thread = scratch / "quick1", two_threads = scratch / "quick2";
  ASSERT_EQ(run_command_line("reproduce jin2003 --quick --no-plot --quiet --threads 1 --out " +
                             one_thread.string())
                .status,
            0);
  ASSERT_EQ(run_command_line("reproduce jin2003 --quick --no-plot --quiet --threads 2 --out " +
                             two_threads.string())
                .status,
            0);
  {
    SCOPED_TRACE("every file, none left half-written");
    for (const char* name : {"fig4a.csv", "fig4a.json", "fig4a_values.csv", "fig4b.csv",
                             "fig4b.json", "fig4b_values.csv", "fig4c.csv", "fig4c.json",
                             "fig4d.csv", "fig4d.json", "report.json", "REPORT.md"})
      EXPECT_TRUE(fs::exists(two_threads / name)) << name;
    for (const auto& entry : fs::directory_iterator(two_threads))
      EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
  {
    SCOPED_TRACE("the ranges, re-derived from the CSVs");
    check_report(two_threads);
  }
  {
    SCOPED_TRACE("each residual from its formula");
    check_residuals(two_threads, "fig4a");
    check_residuals(two_threads, "fig4b");
  }
  {
    SCOPED_TRACE("the same files on one and on two threads");
    for (const char* name : {"fig4a.csv", "fig4a_values.csv", "fig4b.csv", "fig4b_values.csv",
                             "fig4c.csv", "fig4d.csv"})
      EXPECT_EQ(slurp(one_thread / name), slurp(two_threads / name)) << name;
  }
  {
    // Model P's sliding impacts at the paper's V0 = 4.163 m/s, ω = 7 rad/s
    // show in Fig. 4(c) as stretches on the walls, at x = ±b exactly
    SCOPED_TRACE("the slips on the walls");
    const auto meta = nlohmann::json::parse(slurp(two_threads / "fig4c.json"));
    const double b = meta["wall_position_m"];
    int on_wall_paper = 0;
    for (const auto& row : read_csv(two_threads / "fig4c.csv")) {
      if (row.at("mode") == "free") continue;
      EXPECT_NEAR(std::fabs(std::stod(row.at("x"))), b, 1e-12);
      if (row.at("model") == "paper") ++on_wall_paper;
    }
    EXPECT_GT(on_wall_paper, 10);
    for (const auto& slips : meta["slips"]) {
      if (slips["model"] == "paper") {
        EXPECT_GT(slips["sliding_impacts"].get<int>(), 0);
      }
    }
  }
}

TEST(CommittedReproduction, RangesAreRederivedFromTheCsv) {
  const fs::path directory = fs::path(IMPACTLAB_SOURCE_DIR) / "notebooks_data/jin2003";
  ASSERT_TRUE(fs::exists(directory / "report.json"));
  check_report(directory);
  check_residuals(directory, "fig4a");
}

TEST(ReproduceBadInput, UnknownPaperExitsTwo) {
  const ScratchFolder scratch;
  const fs::path out = scratch / "bad";
  const ProgramRun outcome =
      run_command_line(fmt::format("reproduce nosuch --out {}", out.string()));
  EXPECT_TRUE(refused_naming(outcome, "paper"));
  EXPECT_NE(outcome.err.find("nosuch"), std::string::npos) << outcome.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(ReproduceBadInput, BadSceneValueExitsTwo) {
  const ScratchFolder scratch;
  const fs::path out = scratch / "bad_value";
  const ProgramRun outcome =
      run_command_line(fmt::format("reproduce jin2003 --set e_n=2 --out {}", out.string()));
  EXPECT_TRUE(refused_naming(outcome, "e_n"));
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
