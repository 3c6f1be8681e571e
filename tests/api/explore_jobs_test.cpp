// The explorer's jobs (api/explore_jobs.hpp) and requests
// (api/explore_requests.hpp): a newer job of a kind cancels the older at its
// next progress report, a request overtaken by a newer one is refused, the
// number of running jobs is bounded, partial results are read from where the
// reader left off; a page's values go through the scene's own checks; a
// superseded Poincaré section stops at its next point.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/api/explore_jobs.hpp>
#include <impactlab/api/explore_requests.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/io/bad_input.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::ExploreBusy;
using impactlab::ExploreJobControl;
using impactlab::ExploreJobs;
using impactlab::ExploreSuperseded;
using nlohmann::json;
using namespace std::chrono_literals;

// the job's state once it has ended (polls of up to a second)
json ended(ExploreJobs& jobs, std::uint64_t id) {
  for (int attempt = 0; attempt < 60; ++attempt) {
    json state = jobs.poll(id, 0, 1000ms);
    if (state["state"] != "running") return state;
  }
  return nullptr;
}

// work that reports progress until released or cancelled
ExploreJobs::Work waiting_work(std::atomic<bool>& release) {
  return [&release](ExploreJobControl& control) {
    while (!release) {
      control.progress(0.5);
      std::this_thread::sleep_for(1ms);
    }
    return json{{"finished", true}};
  };
}

TEST(ExploreJobs, ANewerJobOfAKindCancelsTheOlderAtItsNextProgressReport) {
  std::atomic<bool> release{false};  // outlives the jobs' threads
  ExploreJobs jobs(4);
  const auto older = jobs.start("trajectory", waiting_work(release));
  const auto other_kind = jobs.start("section", waiting_work(release));
  const auto newer = jobs.start("trajectory", [](ExploreJobControl&) { return json{{"x", 1}}; });
  EXPECT_EQ(ended(jobs, older)["state"], "cancelled");
  const json done = ended(jobs, newer);
  EXPECT_EQ(done["state"], "done");
  EXPECT_EQ(done["result"]["x"], 1);
  // a job of another kind runs on
  EXPECT_EQ(jobs.poll(other_kind, 0, 0ms)["state"], "running");
  release = true;
  EXPECT_EQ(ended(jobs, other_kind)["state"], "done");
}

// A section job reports once per forcing period (SectionRequest::progress):
// a newer section cancels the older mid-run, long before its last point.
TEST(ExploreJobs, ASupersededSectionStopsEarly) {
  const impactlab::Scene scene = impactlab::load_scene("jin2003");
  const impactlab::ExploreLimits limits;
  // 100 transient periods and 5000 points: seconds of work
  const impactlab::SectionView view =
      impactlab::section_view(json{{"transient", 100}, {"points", 5000}}, limits);
  std::atomic<int> reports{0};
  std::atomic<double> last_fraction{0.0};
  ExploreJobs jobs(4);
  const auto older = jobs.start("section", [&](ExploreJobControl& control) {
    return impactlab::run_section(scene, view, {[&](double fraction) {
                                                  ++reports;
                                                  last_fraction = fraction;
                                                  control.progress(fraction);
                                                },
                                                {}});
  });
  // the older run has begun reporting
  for (int wait = 0; wait < 10000 && reports < 10; ++wait) std::this_thread::sleep_for(1ms);
  ASSERT_GE(reports, 10);
  const auto newer = jobs.start("section", [](ExploreJobControl&) { return json{{"x", 1}}; });
  EXPECT_EQ(ended(jobs, older)["state"], "cancelled");
  EXPECT_EQ(ended(jobs, newer)["state"], "done");
  // it stopped early: one report per period of 5100, fractions far below 1
  EXPECT_LT(reports, 5100);
  EXPECT_LT(last_fraction, 0.9);
}

// The reports read the dense output: the points are those of a run without them.
TEST(ExploreRequests, ASectionsProgressReportsLeaveItsPointsAsTheyAre) {
  const impactlab::Scene scene = impactlab::load_scene("jin2003");
  const impactlab::SectionView view =
      impactlab::section_view(json{{"transient", 20}, {"points", 30}}, impactlab::ExploreLimits{});
  std::vector<double> fractions;
  const json reported =
      impactlab::run_section(scene, view, {[&](double f) { fractions.push_back(f); }, {}});
  const json silent = impactlab::run_section(scene, view, {});
  EXPECT_EQ(reported, silent);
  // one report per forcing period of the 20 + 30, rising to 1
  ASSERT_GE(fractions.size(), 49u);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_GT(fractions.back(), 0.97);
  EXPECT_LE(fractions.back(), 1.0);
}

TEST(ExploreJobs, ARequestOvertakenByANewerOneOfItsClientIsRefused) {
  ExploreJobs jobs(4);
  auto quick = [](ExploreJobControl&) { return json::object(); };
  jobs.start("section", quick, 5, "page-a");
  EXPECT_THROW(jobs.start("section", quick, 4, "page-a"), ExploreSuperseded);
  // another page counts its own requests; the same number again is a retry
  EXPECT_NO_THROW(jobs.start("section", quick, 1, "page-b"));
  EXPECT_NO_THROW(jobs.start("section", quick, 5, "page-a"));
}

TEST(ExploreJobs, TheRunningJobsAreBounded) {
  std::atomic<bool> release{false};  // outlives the jobs' threads
  ExploreJobs jobs(2);
  jobs.start("a", waiting_work(release));
  jobs.start("b", waiting_work(release));
  EXPECT_THROW(jobs.start("c", waiting_work(release)), ExploreBusy);
  EXPECT_EQ(jobs.live(), 2);
  release = true;
}

TEST(ExploreJobs, PartialResultsAreReadFromWhereTheReaderLeftOff) {
  ExploreJobs jobs(2);
  const auto id = jobs.start("diagram", [](ExploreJobControl& control) {
    for (int column = 0; column < 5; ++column) control.add_item(json{{"index", column}});
    return json{{"columns", 5}};
  });
  const json state = ended(jobs, id);
  ASSERT_EQ(state["state"], "done");
  const json rest = jobs.poll(id, 3, 0ms);
  ASSERT_EQ(rest["items"].size(), 2u);
  EXPECT_EQ(rest["items"][0]["index"], 3);
  EXPECT_EQ(rest["item_count"], 5);
}

TEST(ExploreJobs, AFailedJobCarriesItsBadInput) {
  ExploreJobs jobs(2);
  const auto id = jobs.start("orbit", [](ExploreJobControl&) -> json {
    throw impactlab::BadInput("b", "0.9", "must be below l");
  });
  const json state = ended(jobs, id);
  EXPECT_EQ(state["state"], "failed");
  EXPECT_EQ(state["error"]["key"], "b");
  EXPECT_EQ(jobs.poll(123456, 0, 0ms), nullptr);
}

TEST(ExploreRequests, APagesValuesPassTheScenesOwnChecks) {
  const impactlab::Scene base = impactlab::load_scene("jin2003");
  const impactlab::ExploreLimits limits;
  const impactlab::Scene changed =
      impactlab::explore_scene(base, json{{"V0", 2.5}, {"model", "paper"}}, limits);
  EXPECT_EQ(changed.number("V0"), 2.5);
  EXPECT_EQ(changed.text("model"), "paper");
  // a key left as it was is not marked as set by the user
  EXPECT_FALSE(impactlab::explore_scene(base, json{{"V0", 1.5}}, limits).assigned.contains("V0"));
  for (const json& values : {json{{"no_such_key", 1}}, json{{"e_n", 1.5}}, json{{"V0", "nan"}},
                             json{{"V0", json::array()}}, json::array()}) {
    SCOPED_TRACE(values.dump());
    EXPECT_THROW(impactlab::explore_scene(base, values, limits), impactlab::BadInput);
  }
}

TEST(ExploreRequests, TheWorkOneRequestMayStartIsBounded) {
  const impactlab::Scene scene = impactlab::load_scene("jin2003");
  const impactlab::ExploreLimits limits;
  EXPECT_THROW(impactlab::trajectory_view(json{{"periods", 1e6}}, limits), impactlab::BadInput);
  EXPECT_THROW(impactlab::section_view(json{{"points", 1e7}}, limits), impactlab::BadInput);
  EXPECT_THROW(impactlab::diagram_view(json{{"key", "V0"}, {"from", 1}, {"to", 2},
                                            {"columns", 1e5}}, scene, limits),
               impactlab::BadInput);
  const impactlab::DiagramView view = impactlab::diagram_view(
      json{{"key", "V0"}, {"from", 1}, {"to", 2}, {"columns", 10}}, scene, limits);
  EXPECT_EQ(view.columns, 10);
}

TEST(ExploreRequests, AnExportedCommandSetsOnlyTheKeysThePageChanged) {
  const impactlab::Scene base = impactlab::load_scene("jin2003");
  const impactlab::ExploreLimits limits;
  const impactlab::Scene scene = impactlab::explore_scene(base, json{{"V0", 2.5}}, limits);
  const impactlab::ExploreExport exported = impactlab::explore_export(
      "trajectory", json{{"periods", 10}}, "jin2003", base, scene, limits);
  ASSERT_EQ(exported.commands.size(), 1u);
  EXPECT_EQ(impactlab::shell_command(exported.commands[0]).substr(0, 46),
            "impactlab simulate jin2003 --set V0=2.5 --peri");
  EXPECT_NE(exported.python_calls[0].find("V0=2.5"), std::string::npos);
  EXPECT_NE(exported.scene_toml.find("V0 = 2.5"), std::string::npos);
  EXPECT_EQ(impactlab::shell_command({"a b", "it's"}), "'a b' 'it'\\''s'");
}

}  // namespace
