// A batch's lanes run their trajectories exactly as the scalar Taylor stepper
// runs them alone: the same events (time, kind, wall, state before and after,
// to the last bit), the same final state, mode, time, termination and
// counters. The jobs cover the hard cases (chattering into a contact phase
// and release, sliding impacts of the paper's model, the Painlevé limit,
// grazing, sticking on a table), lanes whose runs stop early while the
// others go on (more jobs than lanes: a lane takes the next job at once),
// parameter values on both sides of a bifurcation in one batch, and lanes of
// different systems at the same time.
#include <bit>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/model_file/compiled_model.hpp>
#include <impactlab/oscillators/model_file/model_system.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>
#include <impactlab/integrate/taylor_stepper.hpp>
#include <impactlab/simulate/series_batch.hpp>
#include <impactlab/simulate/simulator.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;
using std::numbers::pi;

template <class System>
struct Trajectory {
  System system;
  typename System::State x0;
  typename System::Mode mode{};
  double t_end = 0.0;  // s
  double tolerance = 1e-10;  // rtol; atol and the grazing tolerance a hundredth of it
};

template <class System>
struct Outcome {
  RunResult<typename System::State, typename System::Mode> result;
  std::vector<EventRecord> events;
};

// one run with the Taylor stepper, in `lane` or alone (nullptr)
template <class System>
Outcome<System> run_one(const Trajectory<System>& job, SeriesLane* lane) {
  StepperSettings settings;
  settings.rtol = job.tolerance;
  settings.atol = job.tolerance / 100.0;
  settings.max_step = job.system.max_step();
  settings.series_lane = lane;
  LoopOptions options;
  options.location.grazing_tolerance = settings.atol;
  EventLog log(true);
  Outcome<System> outcome;
  TaylorStepper<System> stepper(settings);
  outcome.result = simulate(job.system, stepper, job.x0, job.mode, 0.0, job.t_end, options, log);
  outcome.events = log.records();
  return outcome;
}

// equal to the last bit (NaN equals NaN of the same bits)
#define EXPECT_SAME_BITS(a, b) \
  EXPECT_EQ(std::bit_cast<std::uint64_t>(double(a)), std::bit_cast<std::uint64_t>(double(b))) \
      << #a << " = " << (a) << " vs " << (b)

template <class System>
void expect_same_run(const Outcome<System>& lane, const Outcome<System>& alone) {
  EXPECT_EQ(lane.result.termination, alone.result.termination);
  EXPECT_EQ(lane.result.mode, alone.result.mode);
  EXPECT_SAME_BITS(lane.result.t, alone.result.t);
  for (std::size_t i = 0; i < alone.result.state.size(); ++i)
    EXPECT_SAME_BITS(lane.result.state[i], alone.result.state[i]);
  EXPECT_EQ(lane.result.counters.steps, alone.result.counters.steps);
  EXPECT_EQ(lane.result.counters.rhs_evaluations, alone.result.counters.rhs_evaluations);
  EXPECT_EQ(lane.result.counters.events, alone.result.counters.events);
  ASSERT_EQ(lane.events.size(), alone.events.size());
  for (std::size_t k = 0; k < alone.events.size(); ++k) {
    SCOPED_TRACE("event " + std::to_string(k));
    const EventRecord& a = lane.events[k];
    const EventRecord& b = alone.events[k];
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.wall, b.wall);
    EXPECT_SAME_BITS(a.t, b.t);
    EXPECT_SAME_BITS(a.q, b.q);
    EXPECT_SAME_BITS(a.qdot_before, b.qdot_before);
    EXPECT_SAME_BITS(a.qdot_after, b.qdot_after);
    EXPECT_SAME_BITS(a.normal_force, b.normal_force);
    EXPECT_SAME_BITS(a.tangential_velocity, b.tangential_velocity);
    EXPECT_SAME_BITS(a.friction_work, b.friction_work);
    EXPECT_SAME_BITS(a.accumulation_error, b.accumulation_error);
  }
}

// Runs the jobs alone, then in `width` lanes, and compares them run by run;
// returns the batch's statistics.
template <class System>
BatchStatistics expect_lanes_equal_alone(const std::vector<Trajectory<System>>& jobs, int width) {
  std::vector<Outcome<System>> alone;
  for (const auto& job : jobs) alone.push_back(run_one(job, nullptr));
  std::vector<Outcome<System>> batched(jobs.size());
  std::size_t next = 0;
  const BatchStatistics statistics = run_in_lanes(width, [&](SeriesLane& lane) {
    if (next == jobs.size()) return false;
    const std::size_t i = next++;
    batched[i] = run_one(jobs[i], &lane);
    return true;
  });
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    SCOPED_TRACE("job " + std::to_string(i));
    expect_same_run(batched[i], alone[i]);
  }
  std::uint64_t steps = 0;
  for (const auto& run : alone) steps += run.result.counters.steps;
  // every step's series came from the batch (a step whose signs needed their
  // slope evaluates once more alone), and lanes ran together
  EXPECT_EQ(statistics.lane_series, steps);
  EXPECT_GT(statistics.lane_series, statistics.evaluations);
  return statistics;
}

PendulumWalls pendulum(double V0, double e_n = 0.3, double mu = 0.6) {
  PendulumWallsParameters p;
  p.V0 = V0;
  p.e_n = e_n;
  p.mu = mu;
  return PendulumWalls(p);
}

double forcing_periods(double n, double omega = 7.0) { return n * 2.0 * pi / omega; }

TEST(SeriesBatch, PendulumHardCasesEqualTheScalarRunsLaneForLane) {
  PendulumWallsParameters defaults;
  const double mu_limit = std::sqrt(1.0 - std::pow(defaults.b / defaults.l, 2)) /
                          (defaults.b / defaults.l);
  using Mode = PendulumWalls::Mode;
  const std::vector<Trajectory<PendulumWalls>> jobs = {
      // chattering into contact phases and releases (the paper's case)
      {pendulum(4.163), {0.0, 0.1, 0.0}, Mode::free, forcing_periods(30)},
      // period-one impacting motion
      {pendulum(1.5), {0.0, 0.1, 0.0}, Mode::free, forcing_periods(40)},
      // stops early while the others go on
      {pendulum(2.9), {0.0, 0.1, 0.0}, Mode::free, forcing_periods(3)},
      // the Painlevé limit: stopped by the model at its first downward slip
      {pendulum(1.5, 0.3, mu_limit), {0.0, 0.1, 0.0}, Mode::free, forcing_periods(60)},
      // plastic impacts: sticking where the wall attracts
      {pendulum(4.163, 0.0), {0.0, 0.1, 0.0}, Mode::free, forcing_periods(20)},
      {pendulum(3.6), {0.02, -0.3, 0.0}, Mode::free, forcing_periods(25)},
      {pendulum(4.4), {-0.05, 0.2, 0.0}, Mode::free, forcing_periods(10)},
  };
  const BatchStatistics statistics = expect_lanes_equal_alone(jobs, 4);
  // a batch of 4 ran mostly full
  EXPECT_GT(static_cast<double>(statistics.lane_series),
            2.0 * static_cast<double>(statistics.evaluations));
}

TEST(SeriesBatch, PaperModelSlidingImpactsEqualTheScalarRunsLaneForLane) {
  std::vector<Trajectory<PaperPendulumWalls>> jobs;
  for (double V0 : {1.5, 4.163, 3.2, 4.6, 2.2}) {
    PendulumWallsParameters p;
    p.V0 = V0;
    jobs.push_back({PaperPendulumWalls(p), {0.0, 0.1, 0.0, 0.0}, PaperPendulumWalls::Mode::free,
                    forcing_periods(V0 == 3.2 ? 2 : 20)});
  }
  expect_lanes_equal_alone(jobs, 3);
}

// the stop across the grazing bifurcation of the linear impact oscillator's
// harmonic orbit (hard_cases_test.cpp): σ = R (1 + δ), impacts for δ < 0,
// none for δ > 0, all in one batch
TEST(SeriesBatch, GrazingOnBothSidesOfTheBifurcationEqualsTheScalarRunsLaneForLane) {
  LinearImpactParameters p;
  p.zeta = 0.05;
  p.A = 1.0;
  p.omega = 2.0;
  const std::complex<double> amplitude =
      p.A / std::complex<double>(1.0 - p.omega * p.omega, 2.0 * p.zeta * p.omega);
  const double R = std::abs(amplitude);
  const LinearImpact::State x0{amplitude.real(),
                               (std::complex<double>(0.0, p.omega) * amplitude).real()};
  std::vector<Trajectory<LinearImpact>> jobs;
  for (double relative : {-1e-2, -1e-6, -1e-9, 1e-9, 1e-6, 1e-2}) {
    p.sigma = R * (1.0 + relative);
    jobs.push_back({LinearImpact(p), x0, LinearImpact::Mode::free, 3.0 * 2.0 * pi / p.omega, 1e-13});
  }
  expect_lanes_equal_alone(jobs, 4);
}

TEST(SeriesBatch, BallChatteringToRestAndStickingEqualsTheScalarRunsLaneForLane) {
  std::vector<Trajectory<BouncingBall>> jobs;
  for (double r : {0.05, 0.0, 0.8, 0.5, 0.3}) {
    BouncingBallParameters p;
    p.r = r;
    jobs.push_back({BouncingBall(p), {0.05, 0.0}, BouncingBall::Mode{}, r == 0.5 ? 0.3 : 3.0});
  }
  expect_lanes_equal_alone(jobs, 4);
}

// the pendulum at V0 (m/s) from a small swing, for `periods` forcing periods
Trajectory<PendulumWalls> swinging(double V0, double periods) {
  return {pendulum(V0), {0.0, 0.1, 0.0}, PendulumWalls::Mode::free, forcing_periods(periods)};
}

// a ball of restitution 0.05 dropped from 5 cm, for t_end (s)
Trajectory<BouncingBall> bouncing(double t_end) {
  BouncingBallParameters ball_parameters;
  ball_parameters.r = 0.05;
  return {BouncingBall(ball_parameters), {0.05, 0.0}, BouncingBall::Mode{}, t_end};
}

// Steppers of two system types in lanes at the same time: the batch
// evaluates each type's requests together, and each lane still equals its
// scalar run.
TEST(SeriesBatch, LanesOfDifferentSystemsEqualTheScalarRuns) {
  const Trajectory<PendulumWalls> swing = swinging(4.163, 10);
  const Trajectory<BouncingBall> bounce = bouncing(2.0);
  const auto swing_alone = run_one(swing, nullptr);
  const auto bounce_alone = run_one(bounce, nullptr);
  std::vector<Outcome<PendulumWalls>> swings(3);
  std::vector<Outcome<BouncingBall>> bounces(3);
  int next = 0;
  const BatchStatistics statistics = run_in_lanes(4, [&](SeriesLane& lane) {
    if (next == 6) return false;
    const int i = next++;
    if (i % 2 == 0)
      swings[i / 2] = run_one(swing, &lane);
    else
      bounces[i / 2] = run_one(bounce, &lane);
    return true;
  });
  for (const auto& run : swings) expect_same_run(run, swing_alone);
  for (const auto& run : bounces) expect_same_run(run, bounce_alone);
  EXPECT_EQ(statistics.lane_series,
            3 * (swing_alone.result.counters.steps + bounce_alone.result.counters.steps));
}

// A lane whose series are the only ones of their kind waits for a partner
// (run_in_lanes' lone_wait_rounds): two pendulums share three lanes with a
// ball, the second ball starting when a pendulum ends. Waiting, the first
// ball's steps run mostly beside the second's, so more series come from
// passes than without waiting; every lane still equals its scalar run, and
// the lone ball finishes.
TEST(SeriesBatch, ALoneKindWaitsForAPartnerAndStillEqualsTheScalarRuns) {
  const Trajectory<PendulumWalls> swing = swinging(1.5, 8);
  const Trajectory<BouncingBall> bounce = bouncing(6.0);
  const auto swing_alone = run_one(swing, nullptr);
  const auto bounce_alone = run_one(bounce, nullptr);
  auto run_batch = [&](int wait_rounds) {
    std::vector<Outcome<PendulumWalls>> swings(2);
    std::vector<Outcome<BouncingBall>> bounces(2);
    int next = 0;
    const BatchStatistics statistics = run_in_lanes(
        3,
        [&](SeriesLane& lane) {
          if (next == 4) return false;
          const int i = next++;
          if (i == 0 || i == 1)
            swings[static_cast<std::size_t>(i)] = run_one(swing, &lane);
          else
            bounces[static_cast<std::size_t>(i - 2)] = run_one(bounce, &lane);
          return true;
        },
        wait_rounds);
    for (const auto& run : swings) expect_same_run(run, swing_alone);
    for (const auto& run : bounces) expect_same_run(run, bounce_alone);
    EXPECT_EQ(statistics.lane_series,
              2 * (swing_alone.result.counters.steps + bounce_alone.result.counters.steps));
    return statistics;
  };
  const BatchStatistics without = run_batch(0);
  const BatchStatistics waiting = run_batch(default_lone_wait_rounds);
  EXPECT_GT(waiting.series_in_passes, without.series_in_passes);
  EXPECT_THROW(run_in_lanes(2, [](SeriesLane&) { return false; }, -1), std::invalid_argument);
}

// Lanes of one system (a basin grid's initial states) are evaluated in
// passes over LaneNumber, all four lanes at once; each still equals its
// scalar run to the last bit, through chattering, contact phases with slip
// reversals (a sign whose slope decides it) and releases.
TEST(SeriesBatch, LanesOfOneSystemInOnePassEqualTheScalarRunsLaneForLane) {
  std::vector<Trajectory<PendulumWalls>> jobs;
  for (int i = 0; i < 9; ++i)
    jobs.push_back({pendulum(4.163), {-0.06 + 0.015 * i, 0.3 - 0.07 * i, 0.0},
                    PendulumWalls::Mode::free, forcing_periods(i == 2 ? 4 : 25)});
  EXPECT_GT(expect_lanes_equal_alone(jobs, 4).series_in_passes, 0u);
  std::vector<Trajectory<PaperPendulumWalls>> paper;
  PendulumWallsParameters p;
  p.V0 = 4.163;
  for (int i = 0; i < 5; ++i)
    paper.push_back({PaperPendulumWalls(p), {0.01 * i, 0.1 + 0.2 * i, 0.0, 0.0},
                     PaperPendulumWalls::Mode::free, forcing_periods(20)});
  expect_lanes_equal_alone(paper, 4);
  std::vector<Trajectory<BouncingBall>> balls;
  BouncingBallParameters q;
  q.r = 0.05;
  for (int i = 0; i < 6; ++i)
    balls.push_back({BouncingBall(q), {0.02 + 0.01 * i, 0.1 * i}, BouncingBall::Mode{}, 3.0});
  expect_lanes_equal_alone(balls, 4);
}

// Lanes of one oscillator with different parameters (a 2D map's points, on
// both sides of the chatter) record the same operations in the same mode,
// so they share passes over lanes, each with its own constants; each still
// equals its scalar run to the last bit. Most of their series come from
// passes: with sixteen lanes waiting, partners in the same mode are found.
// Their event times' roots are refined in lanes together, to the same bits.
TEST(SeriesBatch, LanesOfDifferentParametersShareOnePassAndEqualTheScalarRuns) {
  std::vector<Trajectory<PendulumWalls>> jobs;
  for (int i = 0; i < 12; ++i)
    jobs.push_back({pendulum(1.0 + 0.3 * i, 0.2 + 0.05 * (i % 4), 0.3 + 0.1 * (i % 3)),
                    {0.01 * (i % 5), 0.2, 0.0}, PendulumWalls::Mode::free, forcing_periods(12)});
  const BatchStatistics statistics = expect_lanes_equal_alone(jobs, max_series_lanes);
  EXPECT_GT(2 * statistics.series_in_passes, statistics.lane_series);
  // and their impacts' roots were refined several at a time
  EXPECT_GT(statistics.early_requests, statistics.early_evaluations);
}

// A model file's series (oscillators/model_file/series_program.hpp) in
// lanes: the linear impact oscillator written as a model file, at stops on
// both sides of the chatter (periodic impacts; chatter, sticking and
// release), shares passes, and each lane equals its scalar run to the last
// bit.
TEST(SeriesBatch, ModelFileLanesEqualTheScalarRunsLaneForLane) {
  CompileOptions options;
  options.cache_directory = ::testing::TempDir() + "impactlab_series_batch_model_cache";
  const auto model = compile_model(
      read_model_file(std::string(IMPACTLAB_SOURCE_DIR) +
                      "/oscillators/model_file/examples/linear_impact_model.toml"),
      options);
  ASSERT_TRUE(model->series_refusal.empty()) << model->series_refusal;
  const auto system = [&](double sigma, double r, double omega) {
    std::vector<double> p;
    for (const auto& parameter : model->parameters)
      p.push_back(parameter.name == "sigma" ? sigma
                  : parameter.name == "r"   ? r
                  : parameter.name == "omega" ? omega
                                              : parameter.default_value);
    return ModelSystem<2>(model, p);
  };
  std::vector<Trajectory<ModelSystem<2>>> jobs;
  for (int i = 0; i < 8; ++i) {
    const bool chatter = i % 2 == 1;
    const double omega = chatter ? 0.5 : 2.0 + 0.05 * i;
    jobs.push_back({system(chatter ? 0.0 : 0.1 * (i % 3), 0.5 + 0.05 * i, omega),
                    {chatter ? -0.5 : 0.0, 0.0},
                    ModelSystem<2>::free_mode,
                    10 * 2 * pi / omega});
  }
  EXPECT_GT(expect_lanes_equal_alone(jobs, 8).series_in_passes, 0u);
}

// A job that throws stops its lane; the other lanes finish their jobs, and
// the exception comes out of run_in_lanes.
TEST(SeriesBatch, AJobsExceptionComesOutAfterTheOtherLanesFinish) {
  const Trajectory<PendulumWalls> swing{pendulum(1.5), {0.0, 0.1, 0.0}, PendulumWalls::Mode::free,
                                        forcing_periods(5)};
  const auto alone = run_one(swing, nullptr);
  std::vector<Outcome<PendulumWalls>> runs(3);
  int next = 0;
  EXPECT_THROW(run_in_lanes(2,
                            [&](SeriesLane& lane) {
                              const int i = next++;
                              if (i == 1) throw std::runtime_error("job 1 fails");
                              if (i > 3) return false;
                              runs[i == 0 ? 0 : i - 1] = run_one(swing, &lane);
                              return true;
                            }),
               std::runtime_error);
  expect_same_run(runs[0], alone);
}

TEST(SeriesBatch, RefusesAWidthOutsideItsRange) {
  EXPECT_THROW(run_in_lanes(0, [](SeriesLane&) { return false; }), std::invalid_argument);
  EXPECT_THROW(run_in_lanes(max_series_lanes + 1, [](SeriesLane&) { return false; }),
               std::invalid_argument);
}

// this file's own macro: not seen by the files compiled after it in the
// same unity unit (tests/CMakeLists.txt)
#undef EXPECT_SAME_BITS

}  // namespace
