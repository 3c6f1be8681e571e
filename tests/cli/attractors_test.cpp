// `impactlab attractors` as a user runs it: attractors found by sampling the
// initial states and followed across a parameter (api/attractors_job.hpp).
// * jin2003 is symmetric under the mirror θ → −θ, θ̇ → −θ̇ at the same time:
//   the pivot moves vertically, so the effective gravity g − V0 ω cos ωt does
//   not change under the mirror and the forcing phase does not shift (no half
//   period), the walls sit at ±b and the Newton impact law θ̇⁺ = −e_n θ̇⁻ is
//   odd. An asymmetric orbit therefore comes with its mirror image on the
//   same stroboscopic section, and with a box symmetric about 0 both have
//   basins of the same size: the two attractors' section points are mirror
//   images and their fractions agree within their binomial errors.
// * an attractor keeps its id along a range where it persists, and a birth
//   or death seen by a sweep is reported where it happens;
// * serial, threaded and resumed runs write identical files;
// * bad input exits 2 with one line naming the option.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab::testing;

// attractors.csv's rows as maps from column to text
std::vector<std::map<std::string, std::string>> rows_of(const fs::path& csv) {
  const auto table = read_csv(csv);
  std::vector<std::map<std::string, std::string>> rows;
  for (std::size_t r = 1; r < table.size(); ++r) {
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < table[0].size(); ++c) row[table[0][c]] = table[r][c];
    rows.push_back(row);
  }
  return rows;
}

double number(const std::map<std::string, std::string>& row, const std::string& column) {
  return std::stod(row.at(column));
}

// jin2003 at V0 = 1.5 m/s: around omega = 4 rad/s the pendulum hangs at rest
// or swings onto one wall once per period, right or left: a mirror pair of
// period-1 orbits with one impact each. The box is symmetric under the mirror.
const std::string mirror_box = " --box initial.theta=-0.06:0.06 --box initial.theta_dot=-1:1";

TEST(AttractorsCli, AnAsymmetricOrbitAndItsMirrorImageAreTwoAttractorsOfEqualBasins) {
  const ScratchFolder scratch;
  const fs::path out = scratch / "mirror";
  const ProgramRun run = run_command_line(
      "attractors jin2003 --set V0=1.5 --param omega=4:4:1 --samples 300 --threads 2" +
      mirror_box + " --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.err;
  std::vector<std::map<std::string, std::string>> impacting;
  double total = 0.0;
  for (const auto& row : rows_of(out / "attractors.csv")) {
    total += number(row, "fraction");
    if (row.at("attractor") != "0" && row.at("period") == "1" &&
        row.at("impacts_per_cycle") == "1")
      impacting.push_back(row);
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
  ASSERT_EQ(impacting.size(), 2u) << slurp(out / "attractors.csv");
  const auto& a = impacting[0];
  const auto& b = impacting[1];
  EXPECT_NE(a.at("attractor"), b.at("attractor"));
  // mirror images: q -> -q, qdot -> -qdot at the same forcing phase, each a
  // wall impact away from the hanging rest (|q| well above the tolerance)
  EXPECT_GT(std::fabs(number(a, "q")), 0.01);
  EXPECT_NEAR(number(a, "q"), -number(b, "q"), 1e-8);
  EXPECT_NEAR(number(a, "qdot"), -number(b, "qdot"), 1e-8);
  EXPECT_NEAR(number(a, "min_impact_speed"), number(b, "min_impact_speed"), 1e-6);
  // and so are their section points in attractor_points.csv
  std::map<std::string, std::vector<double>> q_of;
  for (const auto& row : rows_of(out / "attractor_points.csv"))
    q_of[row.at("attractor")].push_back(number(row, "q"));
  ASSERT_EQ(q_of[a.at("attractor")].size(), 1u);
  EXPECT_NEAR(q_of[a.at("attractor")][0], -q_of[b.at("attractor")][0], 1e-8);
  // equal basins within their binomial errors (3 standard errors of the difference)
  const double difference = number(a, "fraction") - number(b, "fraction");
  const double error = std::hypot(number(a, "fraction_error"), number(b, "fraction_error"));
  EXPECT_GT(number(a, "fraction"), 0.05);
  EXPECT_LE(std::fabs(difference), 3.0 * error) << slurp(out / "attractors.csv");
  EXPECT_NEAR(number(a, "fraction_error"),
              std::sqrt(number(a, "fraction") * (1.0 - number(a, "fraction")) / 300.0), 1e-15);
  // the events of a single value: none
  const auto meta = nlohmann::json::parse(slurp(out / "meta.json"));
  EXPECT_TRUE(meta["attractor_events"]["events"].empty());
  EXPECT_EQ(meta["sweep"]["samples"], 300);
  EXPECT_EQ(meta["sweep"]["box"][0]["unit"], "rad");
}

TEST(AttractorsCli, WithLyapunovEachAttractorHasItsExponent) {
  // the mirror pair's exponents are equal and negative (stable orbits); the
  // hanging rest's pair of Floquet multipliers is complex, so both exponents
  // are half their sum, the trace's -d/(m l^2): -d/(2 m l^2)
  const ScratchFolder scratch;
  const fs::path out = scratch / "lyapunov";
  ASSERT_EQ(run_command_line("attractors jin2003 --param omega=4:4:1 --samples 20 --lyapunov" +
                             mirror_box + " --quiet --out " + out.string())
                .status,
            0);
  std::vector<double> pair;
  int rests = 0;
  for (const auto& row : rows_of(out / "attractors.csv")) {
    if (row.at("impacts_per_cycle") == "1") pair.push_back(number(row, "lyapunov"));
    if (row.at("attractor") != "0" && row.at("impacts_per_cycle") == "0") {
      ++rests;
      const double d = 0.01, m = 0.5, l = 0.7;  // jin2003's damping, mass, length
      EXPECT_NEAR(number(row, "lyapunov"), -d / (2.0 * m * l * l), 0.1 * d / (2.0 * m * l * l));
      EXPECT_EQ(row.at("min_impact_speed"), "nan");  // no impact
    }
  }
  EXPECT_EQ(rests, 1);
  ASSERT_EQ(pair.size(), 2u);
  EXPECT_LT(pair[0], 0.0);
  EXPECT_NEAR(pair[0], pair[1], 1e-9);
}

TEST(AttractorsCli, IdsPersistAlongTheRangeAndBirthsAndDeathsAreReportedWhereTheyHappen) {
  // omega from 3.75 to 4.25 rad/s: the mirror pair exists from the start and
  // is gone by 4.2 (the basins scan of docs/analysis.md); the hanging rest is
  // not there at 3.75 and appears by 3.85
  const ScratchFolder scratch;
  const fs::path out = scratch / "range";
  const ProgramRun run = run_command_line(
      "attractors jin2003 --set V0=1.5 --param omega=3.75:4.25:11 --samples 60 --threads 2" +
      mirror_box + " --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.err;
  // per id: the values where it is found, and its class
  std::map<int, std::vector<double>> found_at;
  std::map<int, std::set<std::string>> classes;
  std::set<double> values;
  for (const auto& row : rows_of(out / "attractors.csv")) {
    values.insert(number(row, "omega"));
    const int id = std::stoi(row.at("attractor"));
    if (id == 0) continue;
    found_at[id].push_back(number(row, "omega"));
    classes[id].insert(row.at("period") + "," + row.at("impacts_per_cycle"));
  }
  ASSERT_EQ(values.size(), 11u);
  std::vector<int> pair, rest;
  for (const auto& [id, at] : found_at) {
    EXPECT_EQ(classes[id].size(), 1u) << id;  // one class per id along the range
    if (*classes[id].begin() == "1,1") pair.push_back(id);
    if (*classes[id].begin() == "1,0") rest.push_back(id);
  }
  // the pair: two ids, each found at every value from 3.75 on without a
  // gap, gone before 4.2
  ASSERT_EQ(pair.size(), 2u) << slurp(out / "attractors.csv");
  for (const int id : pair) {
    const auto& at = found_at[id];
    EXPECT_EQ(at.front(), 3.75) << id;
    EXPECT_GE(at.back(), 4.1 - 1e-12) << id;
    EXPECT_LT(at.back(), 4.2 - 1e-12) << id;
    const auto first = std::find(values.begin(), values.end(), at.front());
    EXPECT_TRUE(std::equal(at.begin(), at.end(), first)) << id;  // no gap
  }
  ASSERT_EQ(rest.size(), 1u) << slurp(out / "attractors.csv");
  const double born = found_at[rest[0]].front();
  EXPECT_GT(born, 3.75);
  EXPECT_LE(born, 3.85 + 1e-12);
  // the events: the rest appears where it is first found, each of the pair
  // vanishes after the last value it is found at
  const auto events = nlohmann::json::parse(slurp(out / "meta.json"))["attractor_events"];
  EXPECT_EQ(events["parameter"], "omega");
  int appear = 0, vanish = 0;
  for (const auto& event : events["events"]) {
    const int id = event["attractor"];
    if (event["type"] == "appear" && id == rest[0]) {
      ++appear;
      EXPECT_EQ(event["to_value"].get<double>(), born);
    }
    if (event["type"] == "vanish" && (id == pair[0] || id == pair[1])) {
      ++vanish;
      EXPECT_EQ(event["from_value"].get<double>(), found_at[id].back());
    }
    EXPECT_NE(event["type"], "merge") << event.dump();
  }
  EXPECT_EQ(appear, 1) << events.dump(1);
  EXPECT_EQ(vanish, 2) << events.dump(1);
}

const std::string small_run =
    "attractors jin2003 --set V0=1.5 --param omega=3.9:4.1:3 --samples 12" + mirror_box;

TEST(AttractorsCli, SerialThreadedAndResumedRunsWriteIdenticalFiles) {
  const ScratchFolder scratch;
  const auto run = [&](const std::string& extra, const std::string& folder) {
    return run_command_line(small_run + extra + " --out " + (scratch / folder).string());
  };
  ASSERT_EQ(run(" --threads 1", "serial").status, 0);
  ASSERT_EQ(run(" --threads 2", "threaded").status, 0);
  EXPECT_EQ(run(" --stop-after 7", "resumed").status, 3);
  EXPECT_FALSE(fs::exists(scratch / "resumed" / "attractors.csv"));
  ASSERT_EQ(run(" --resume --threads 2", "resumed").status, 0);
  for (const char* file : {"attractors.csv", "attractor_points.csv", "samples.csv"})
    for (const char* other : {"threaded", "resumed"}) {
      const std::string serial = slurp(scratch / "serial" / file);
      EXPECT_FALSE(serial.empty()) << file;
      EXPECT_EQ(serial, slurp(scratch / other / file)) << file << " " << other;
    }
  // another seed draws other initial states
  ASSERT_EQ(run(" --seed 2", "seed2").status, 0);
  EXPECT_NE(slurp(scratch / "serial" / "samples.csv"), slurp(scratch / "seed2" / "samples.csv"));
  if (!mpirun_found()) GTEST_SKIP() << "no mpirun";
  const ProgramRun mpi =
      run_command_line(small_run + " --out " + (scratch / "mpi").string(), {.mpi_ranks = 2});
  if (mpi.err.find("built without MPI") != std::string::npos) GTEST_SKIP() << "built without MPI";
  ASSERT_EQ(mpi.status, 0) << mpi.err;
  for (const char* file : {"attractors.csv", "attractor_points.csv", "samples.csv"})
    EXPECT_EQ(slurp(scratch / "serial" / file), slurp(scratch / "mpi" / file)) << file;
}

TEST(AttractorsCli, TheDefaultBoxLiesInsideTheWalls) {
  const ScratchFolder scratch;
  const fs::path out = scratch / "default";
  ASSERT_EQ(run_command_line("attractors jin2003 --param omega=7:7:1 --samples 4 --quiet --out " +
                             out.string())
                .status,
            0);
  const auto box = nlohmann::json::parse(slurp(out / "meta.json"))["sweep"]["box"];
  ASSERT_EQ(box.size(), 2u);
  const double wall = std::asin(0.05 / 0.7);  // asin(b/l), jin2003's walls
  EXPECT_EQ(box[0]["key"], "initial.theta");
  EXPECT_LT(box[0]["to"].get<double>(), wall);
  EXPECT_GT(box[0]["from"].get<double>(), -wall);
  EXPECT_GT(box[0]["to"].get<double>(), wall / 2.0);
  EXPECT_EQ(box[1]["key"], "initial.theta_dot");
  EXPECT_NEAR(box[1]["to"].get<double>() - box[1]["from"].get<double>(), 2.0, 1e-12);
  for (const auto& row : rows_of(out / "samples.csv")) {
    EXPECT_LE(std::fabs(number(row, "initial.theta")), box[0]["to"].get<double>());
  }
}

TEST(AttractorsCli, BadInputExitsWithTwoAndOneLineNamingTheOption) {
  const std::string base = "attractors jin2003 --param omega=4:4.2:3 --samples 4";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {base + " --box initial.nope=0:1", "--box"},                   // unknown key
      {base + " --box initial.theta=-0.2:0.2", "--box"},             // past the walls
      {base + " --box initial.theta=0.1", "--box"},                  // malformed
      {base + " --box e_t=-0.5:0", "--box"},                         // not read by newton
      {base + " --box omega=1:2", "--box"},                          // the swept key
      {"attractors jin2003 --param omega=4:4.2:3 --samples 0", "--samples"},
      {"attractors jin2003 --param omega=4:4.2 --samples 4", "--param"},  // malformed
      {"attractors jin2003 --param nope=4:4.2:3 --samples 4", "--param"},
      {base + " --match-tol 0", "--match-tol"},
      // 1000 values x 10^7 samples: sized against limits.max_rows before any run
      {"attractors jin2003 --param omega=4:4.2:1000 --samples 10000000", "--samples"},
  };
  for (const auto& [command_line, option] : bad) {
    const ScratchFolder scratch;
    const ProgramRun run = run_command_line(command_line + " --out " + (scratch / "o").string());
    EXPECT_TRUE(refused_naming(run, option)) << command_line << "\n" << run.err;
    EXPECT_FALSE(fs::exists(scratch / "o" / "attractors.csv")) << command_line;
  }
}

}  // namespace
