// The stepper view (simulate/stepper_view.hpp) through which the library's
// flows drive every stepper: for each stepper it reports the stepper's own
// flags, and the event loop run on the view is the loop run on the stepper
// itself, event for event and bit for bit, the Taylor stepper's own event
// location and the scan of the others' dense output alike.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/integrate/stepper_names.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/simulate/stepper_view.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::EventLog;
using impactlab::EventRecord;
using impactlab::LinearImpact;
using impactlab::SteppingView;
using impactlab::SteppingViewOf;

struct LoopRun {
  std::vector<EventRecord> events;
  std::vector<double> final_state;
  std::uint64_t steps = 0;
  std::uint64_t rhs_evaluations = 0;
};

template <class Stepper>
LoopRun run(const LinearImpact& system, Stepper& stepper) {
  impactlab::LoopOptions options;
  options.location.grazing_tolerance = 1e-12;
  EventLog log(true);
  const double t_end = 40.0 * 2.0 * 3.141592653589793 / system.parameters().omega;
  const auto result = impactlab::simulate(system, stepper, LinearImpact::State{0.0, 0.0},
                                          LinearImpact::Mode::free, 0.0, t_end, options, log);
  EXPECT_EQ(result.termination, impactlab::Termination::completed);
  return {log.records(), {result.state.begin(), result.state.end()}, result.counters.steps,
          result.counters.rhs_evaluations};
}

class StepperView : public ::testing::TestWithParam<std::string_view> {};

TEST_P(StepperView, ReportsTheFlagsAndRunsTheLoopOfTheStepperItself) {
  impactlab::LinearImpactParameters p;  // the default motion impacts every forcing period
  const LinearImpact system(p);
  impactlab::StepperSettings settings;
  settings.rtol = 1e-10;
  settings.atol = 1e-12;
  settings.max_step = system.max_step();
  impactlab::with_stepper_type<LinearImpact>(GetParam(), [&]<class Stepper>() {
    Stepper stepper(settings);
    SteppingViewOf<LinearImpact, Stepper> owned(settings);
    SteppingView<LinearImpact>& view = owned;
    EXPECT_EQ(view.scans_cheaply(), Stepper::has_cheap_scan);
    EXPECT_EQ(view.polishes(), Stepper::has_polish);
    EXPECT_EQ(view.locates_own_events(), GetParam() == "taylor");
    if (!view.locates_own_events()) {
      EXPECT_THROW((void)view.locate_first_event(system, LinearImpact::Mode::free, 0.0, 1.0, {}, 0),
                   std::logic_error);
    }

    const LoopRun direct = run(system, stepper);
    const LoopRun viewed = run(system, view);
    ASSERT_GT(direct.events.size(), 20u);
    ASSERT_EQ(direct.events.size(), viewed.events.size());
    for (std::size_t i = 0; i < direct.events.size(); ++i) {
      EXPECT_EQ(direct.events[i].t, viewed.events[i].t) << "event " << i;
      EXPECT_EQ(direct.events[i].kind, viewed.events[i].kind) << "event " << i;
      EXPECT_EQ(direct.events[i].qdot_after, viewed.events[i].qdot_after) << "event " << i;
    }
    EXPECT_EQ(direct.final_state, viewed.final_state);
    EXPECT_EQ(direct.steps, viewed.steps);
    EXPECT_EQ(direct.rhs_evaluations, viewed.rhs_evaluations);
  });
}

INSTANTIATE_TEST_SUITE_P(AllSteppers, StepperView, ::testing::ValuesIn(impactlab::stepper_names),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace IMPACTLAB_TEST_FILE_SCOPE
