// The sweep's building blocks: parameter axes, the cutting into tasks (which
// must not depend on threads or ranks), the classification of section points,
// and the checkpoint lines (which must give back every bit).
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include <impactlab/analysis/sweep.hpp>
#include <impactlab/io/bad_input.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::SweepPlan;
using impactlab::testing::bad_input_key;

TEST(SweepAxis, ParsesAndSpacesValuesEvenlyWithExactEnds) {
  const auto axis = impactlab::parse_axis("omega=5:9:400", "--param");
  EXPECT_EQ(axis.name, "omega");
  EXPECT_EQ(axis.count, 400);
  EXPECT_EQ(axis.value(0), 5.0);
  EXPECT_EQ(axis.value(399), 9.0);
  EXPECT_DOUBLE_EQ(axis.value(133), 5.0 + 4.0 * 133.0 / 399.0);
  EXPECT_EQ(impactlab::parse_axis("V0=2:1:1", "--param").value(0), 2.0);
  // refused, naming the option the axis came from
  for (const char* text : {"omega=5:9", "omega=5:9:2.5", "omega=5:inf:3", "=5:9:3"})
    EXPECT_EQ(bad_input_key([&] { impactlab::parse_axis(text, "--param"); }), "--param") << text;
}

TEST(SweepTasks, OneDimensionalChunksCoverEveryValueOncePerDirection) {
  SweepPlan plan;
  plan.axes = {impactlab::parse_axis("omega=5:9:10", "--param")};
  plan.direction = impactlab::SweepDirection::both;
  plan.chunks = 3;
  const auto tasks = impactlab::sweep_tasks(plan);
  ASSERT_EQ(tasks.size(), 6u);
  std::multiset<std::pair<int, int>> seen;  // (direction, index)
  for (const auto& task : tasks) {
    for (std::size_t p = 1; p < task.points.size(); ++p)  // contiguous, in the direction
      EXPECT_EQ(task.points[p][0] - task.points[p - 1][0], task.direction);
    for (const auto& point : task.points) seen.insert({task.direction, point[0]});
  }
  EXPECT_EQ(seen.size(), 20u);
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(seen.count({1, i}), 1u);
    EXPECT_EQ(seen.count({-1, i}), 1u);
  }
}

TEST(SweepTasks, TwoDimensionalRowsFollowTheFirstParameterUp) {
  SweepPlan plan;
  plan.axes = {impactlab::parse_axis("omega=5:9:4", "--param"),
               impactlab::parse_axis("V0=1:2:3", "--param")};
  const auto tasks = impactlab::sweep_tasks(plan);
  ASSERT_EQ(tasks.size(), 3u);
  for (int j = 0; j < 3; ++j) {
    ASSERT_EQ(tasks[j].points.size(), 4u);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(tasks[j].points[i], (std::array<int, 2>{i, j}));
  }
}

TEST(SweepTasks, ASampledPlansSamplesComeInTasksOfOneValueInSampleOrder) {
  SweepPlan plan;
  plan.axes = {impactlab::parse_axis("omega=5:9:2", "--param")};
  plan.samples = 2 * impactlab::samples_per_task + 10;
  const auto tasks = impactlab::sweep_tasks(plan);
  ASSERT_EQ(tasks.size(), 6u);  // per value: two full tasks and one of 10
  int id = 0;
  for (int i = 0; i < 2; ++i) {
    int sample = 0;
    for (int t = 0; t < 3; ++t, ++id) {
      EXPECT_EQ(tasks[id].id, id);
      EXPECT_EQ(tasks[id].points.size(),
                static_cast<std::size_t>(t < 2 ? impactlab::samples_per_task : 10));
      for (const auto& point : tasks[id].points)
        EXPECT_EQ(point, (std::array<int, 2>{i, sample++}));
    }
    EXPECT_EQ(sample, plan.samples);
  }
}

impactlab::SectionResult points_of(const std::vector<std::array<double, 2>>& states) {
  impactlab::SectionResult result;
  for (const auto& s : states) result.points.push_back({0.0, s[0], s[1], 0});
  result.periods_recorded = static_cast<double>(states.size());
  return result;
}

TEST(Classify, FindsTheSmallestRepeatingPeriod) {
  SweepPlan plan;
  std::vector<std::array<double, 2>> period_three;
  for (int k = 0; k < 30; ++k)
    period_three.push_back({0.1 * (k % 3) + 1e-9 * (k % 2), -0.2 * (k % 3)});
  auto result = points_of(period_three);
  result.impacts = 45;
  result.contact_phases = 2;
  const auto c = impactlab::classify(result, plan);
  EXPECT_EQ(c.period, 3);
  EXPECT_DOUBLE_EQ(c.impacts_per_period, 1.5);
  EXPECT_TRUE(c.contact);

  // the logistic map at r = 4 (chaotic) repeats nothing
  std::vector<std::array<double, 2>> chaotic;
  double x = 0.3;
  for (int k = 0; k < 64; ++k) {
    chaotic.push_back({x, 1.0 - x});
    x = 4.0 * x * (1.0 - x);
  }
  EXPECT_EQ(impactlab::classify(points_of(chaotic), plan).period, 0);
  // a drift above the tolerance is not periodic either
  std::vector<std::array<double, 2>> drifting;
  for (int k = 0; k < 20; ++k) drifting.push_back({1.0 + 1e-5 * k, 0.0});
  EXPECT_EQ(impactlab::classify(points_of(drifting), plan).period, 0);
}

TEST(Checkpoint, LinesGiveBackEveryBit) {
  impactlab::SweepRecord record;
  record.task = 7;
  record.position = 3;
  record.index = {12, 4};
  record.direction = -1;
  record.result.points = {{1.0 / 3.0, std::nextafter(0.1, 1.0), -2.5e-300, 1},
                          {std::numbers::pi, -0.0, 1e300, -1}};
  record.result.final_state = impactlab::ContinuationState{{0.1 + 0.2, -1.0 / 7.0, 0.0}, 2};
  record.result.lyapunov = -std::numeric_limits<double>::infinity();
  record.result.termination = impactlab::SectionTermination::completed;
  record.result.impacts = 123;
  record.result.periods_recorded = 50;
  record.classification = {2, 2.46, true};
  const auto back = impactlab::from_json_line(impactlab::to_json_line(record));
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->task, 7);
  EXPECT_EQ(back->index, record.index);
  EXPECT_EQ(back->direction, -1);
  ASSERT_EQ(back->result.points.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(back->result.points[k].t, record.result.points[k].t);
    EXPECT_EQ(back->result.points[k].q, record.result.points[k].q);
    EXPECT_EQ(back->result.points[k].qdot, record.result.points[k].qdot);
    EXPECT_EQ(back->result.points[k].wall, record.result.points[k].wall);
  }
  EXPECT_EQ(back->result.final_state->state, record.result.final_state->state);
  EXPECT_EQ(back->result.final_state->mode, 2);
  EXPECT_EQ(back->result.lyapunov, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(back->classification.impacts_per_period, 2.46);
  EXPECT_TRUE(std::isnan(back->result.min_impact_speed));  // no impact speed: NaN kept

  record.result.lyapunov = std::numeric_limits<double>::quiet_NaN();
  record.result.final_state.reset();
  const auto nan_back = impactlab::from_json_line(impactlab::to_json_line(record));
  ASSERT_TRUE(nan_back.has_value());
  EXPECT_TRUE(std::isnan(nan_back->result.lyapunov));
  EXPECT_FALSE(nan_back->result.final_state.has_value());

  // a line cut short by a kill is rejected, not half read
  const std::string line = impactlab::to_json_line(record);
  EXPECT_FALSE(impactlab::from_json_line(line.substr(0, line.size() / 2)).has_value());
}

}  // namespace
