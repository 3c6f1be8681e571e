// `impactlab compare` and its library part (api/compare.hpp):
// * the agreement numbers on hand-made impact sequences (where they agree,
//   where they separate), the model list parser;
// * the program on jin2003 with newton,rigid: complete outputs, and, since
//   the rigid model at radius 0 with the spin locked is Model N, the two
//   impact columns agree to 1e-9 (the rigid model's reduction, docs/rigidbody.md);
// * a model the scene rejects (an unknown one) exits 2 with one line naming
//   the key and the value, and writes nothing.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <impactlab/api/compare.hpp>
#include <impactlab/io/bad_input.hpp>

#include "support/test_support.hpp"

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab::testing;

EventRecord impact(double t, int wall) {
  EventRecord e;
  e.t = t;
  e.wall = wall;
  e.kind = EventKind::impact;
  return e;
}

ModelRun run_with(const std::string& model, std::vector<EventRecord> impacts) {
  ModelRun run;
  run.model = model;
  run.impacts = impacts;
  run.output.events = impacts;
  return run;
}

TEST(CompareNumbers, SequencesAgreeUntilTheySeparate) {
  Comparison comparison;
  comparison.period = 1.0;
  comparison.runs.push_back(run_with("a", {impact(0.1, 1), impact(0.5, -1), impact(0.9, 1)}));
  comparison.runs.push_back(
      run_with("b", {impact(0.1 + 1e-8, 1), impact(0.5, -1), impact(0.95, 1), impact(1.2, -1)}));
  comparison.runs.push_back(run_with("c", {impact(0.1, -1)}));
  const auto numbers = comparison_numbers(comparison);
  ASSERT_EQ(numbers["pairs"].size(), 2u);
  const auto& ab = numbers["pairs"][0];
  EXPECT_EQ(ab["matched_impacts"], 3);
  EXPECT_EQ(ab["agreeing_impacts"], 2);
  EXPECT_EQ(ab["first_disagreement"], 2);
  EXPECT_NEAR(ab["first_disagreement_t_s"].get<double>(), 0.9, 1e-15);
  EXPECT_NEAR(ab["max_abs_dt_agreeing_s"].get<double>(), 1e-8, 1e-15);
  const auto& ac = numbers["pairs"][1];
  EXPECT_EQ(ac["agreeing_impacts"], 0);  // other wall
  EXPECT_EQ(numbers["models"]["b"]["impacts"], 4);
}

TEST(CompareNumbers, ModelListIsParsedAndChecked) {
  EXPECT_EQ(parse_model_list("newton,rigid"), (std::vector<std::string>{"newton", "rigid"}));
  EXPECT_EQ(bad_input_key([] { parse_model_list("newton,,rigid"); }), "models");
  EXPECT_EQ(bad_input_key([] { parse_model_list("newton,newton"); }), "models");
  EXPECT_EQ(bad_input_key([] { parse_model_list(""); }), "models");
}

TEST(CompareCommand, NewtonAndReducedRigidAgreeOnJin2003) {
  const ScratchFolder scratch;
  const auto out = scratch / "jin2003";
  const ProgramRun outcome = run_command_line(
      "compare jin2003 --models newton,rigid --periods 30 --quiet --out " + out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  for (const char* file : {"compare_impacts.csv", "compare_contacts.csv", "compare_section.csv",
                           "summary.md", "compare.json"})
    EXPECT_TRUE(std::filesystem::exists(out / file)) << file;

  const auto rows = read_csv(out / "compare_impacts.csv");
  ASSERT_GT(rows.size(), 20u);
  const auto& header = rows.front();
  const auto find = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const std::size_t t_newton = find("t_newton"), t_rigid = find("t_rigid");
  const std::size_t q_newton = find("qdot_after_newton"), q_rigid = find("qdot_after_rigid");
  ASSERT_LT(t_rigid, header.size());
  for (std::size_t i = 1; i < rows.size(); ++i) {
    ASSERT_FALSE(rows[i][t_newton].empty());
    ASSERT_FALSE(rows[i][t_rigid].empty());
    EXPECT_NEAR(std::stod(rows[i][t_newton]), std::stod(rows[i][t_rigid]), 1e-9) << "row " << i;
    EXPECT_NEAR(std::stod(rows[i][q_newton]), std::stod(rows[i][q_rigid]), 1e-9) << "row " << i;
  }
  const auto meta = nlohmann::json::parse(slurp(out / "compare.json"));
  EXPECT_EQ(meta["models"], nlohmann::json({"newton", "rigid"}));
  EXPECT_EQ(meta["runs"]["rigid"]["scene"]["keys"]["model"]["value"], "rigid");
  EXPECT_EQ(meta["numbers"]["pairs"][0]["first_disagreement"], nullptr);
  // 30 periods: 31 strobe points per model (t0 included)
  EXPECT_EQ(read_csv(out / "compare_section.csv").size(), 1u + 31u);
  EXPECT_NE(slurp(out / "summary.md").find("reduces to Model N"), std::string::npos);
}

// A model specification with settings of its own, as reproduce --models
// takes it: the rigid run is the one `simulate` makes with those settings,
// impact for impact (it was refused as an unknown model)
TEST(CompareCommand, AModelSpecificationCarriesItsOwnSettings) {
  const ScratchFolder scratch;
  const ProgramRun outcome = run_command_line(
      "compare jin2003 --models newton,rigid:radius=0.01:spin=free --periods 10 --quiet --out " +
      (scratch / "compare").string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const ProgramRun alone = run_command_line(
      "simulate jin2003 --set model=rigid --set radius=0.01 --set spin=free --periods 10 --quiet "
      "--out " + (scratch / "simulate").string());
  ASSERT_EQ(alone.status, 0) << alone.err;
  const auto compared = read_csv(scratch / "compare" / "compare_impacts.csv");
  const auto& header = compared.front();
  const auto column = static_cast<std::size_t>(
      std::find(header.begin(), header.end(), "t_rigid:radius=0.01:spin=free") - header.begin());
  ASSERT_LT(column, header.size());
  std::vector<std::string> times;
  for (const auto& row : read_csv(scratch / "simulate" / "events.csv"))
    if (row.size() > 1 && row[1] == "impact") times.push_back(row[0]);
  ASSERT_GT(times.size(), 5u);
  std::size_t k = 0;
  for (std::size_t i = 1; i < compared.size(); ++i)
    if (!compared[i][column].empty()) {
      ASSERT_LT(k, times.size());
      EXPECT_EQ(std::stod(compared[i][column]), std::stod(times[k++])) << "impact " << i;
    }
  EXPECT_EQ(k, times.size());
}

TEST(CompareCommand, RejectedModelExitsTwoAndWritesNothing) {
  const ScratchFolder scratch;
  const auto out = scratch / "unknown";
  const ProgramRun outcome = run_command_line(
      "compare jin2003 --models newton,bogus --periods 2 --quiet --out " + out.string());
  EXPECT_TRUE(refused_naming(outcome, "model"));
  EXPECT_NE(outcome.err.find("model = bogus"), std::string::npos) << outcome.err;
  EXPECT_FALSE(std::filesystem::exists(out / "compare_impacts.csv"));
  EXPECT_FALSE(std::filesystem::exists(out / "compare.json"));
}

// A path is data, never shell text: an --out that would close a quoted
// shell word and run `touch` must reach the plot script whole.
TEST(CompareCommand, HostileOutDirectoryIsNotShellText) {
  const ScratchFolder scratch;
  const auto marker = scratch / "INJECTED";
  const std::string hostile = (scratch / ("d';touch " + marker.string() + ";'")).string();
  const ProgramRun outcome = run_impactlab(
      {"compare", "jin2003", "--models", "newton", "--periods", "2", "--quiet", "--out", hostile});
  EXPECT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(hostile) / "compare.json"));
  EXPECT_FALSE(std::filesystem::exists(marker)) << "the plot command ran shell text";
}

TEST(CompareCommand, MalformedModelListExitsTwo) {
  const ScratchFolder scratch;
  const ProgramRun outcome =
      run_command_line("compare jin2003 --models newton,,rigid --periods 2 --quiet --out " +
                       (scratch / "list").string());
  EXPECT_TRUE(refused_naming(outcome, "--models"));
  EXPECT_NE(outcome.err.find("--models = newton,,rigid"), std::string::npos) << outcome.err;
}

}  // namespace
}  // namespace impactlab
