// DecoratedSystem (analysis/decorated_system.hpp): every optional hook of the
// hybrid-system concept that its base has is forwarded, and with nothing
// switched on it is its base number for number: the same events at the same
// times, on every stepper, and the same tangent dynamics. The analyses run it
// in place of the plain system (Floquet, Lyapunov, continuation), so a
// difference here would be a difference in every result.
#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/analysis/decorated_system.hpp>
#include <impactlab/analysis/flow_setup.hpp>
#include <impactlab/analysis/variational.hpp>
#include <impactlab/core/has_jacobian.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>
#include <impactlab/simulate/simulator.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::BouncingBall;
using impactlab::DecoratedSystem;
using impactlab::EventLog;
using impactlab::LinearImpact;
using impactlab::PaperPendulumWalls;
using impactlab::PendulumWalls;
using impactlab::Variational;

// every optional hook the base has, the decorated system has
template <class Base>
constexpr bool forwards_every_hook() {
  using Decorated = DecoratedSystem<Base>;
  static_assert(impactlab::HybridSystem<Decorated>);
  static_assert(impactlab::HasExactFlow<Base> == impactlab::HasExactFlow<Decorated>);
  static_assert(impactlab::HasJacobian<Base> == impactlab::HasJacobian<Decorated>);
  static_assert(impactlab::HasSeriesRhs<Base> == impactlab::HasSeriesRhs<Decorated>);
  static_assert(impactlab::tangent_dimension_of<Base> == impactlab::tangent_dimension_of<Decorated>);
  static_assert(impactlab::affine_flow_of<Base>() == Decorated::affine_flow);
  static_assert(impactlab::error_scale_groups_of<Base>() ==
                impactlab::error_scale_groups_of<Decorated>());
  static_assert(impactlab::HasStateNames<Base> == impactlab::HasStateNames<Decorated>);
  if constexpr (impactlab::HasJacobian<Base>) {
    static_assert(impactlab::HasSeriesRhs<Variational<Base>> ==
                  impactlab::HasSeriesRhs<Variational<Decorated>>);
    static_assert(impactlab::HasExactFlow<Variational<Base>> ==
                  impactlab::HasExactFlow<Variational<Decorated>>);
  }
  return true;
}
static_assert(forwards_every_hook<PendulumWalls>());
static_assert(forwards_every_hook<PaperPendulumWalls>());
static_assert(forwards_every_hook<LinearImpact>());
static_assert(forwards_every_hook<BouncingBall>());

struct Run {
  std::vector<impactlab::EventRecord> events;
  std::vector<double> final_state;
};

template <class System>
Run run(const System& system, const typename System::State& x0, typename System::Mode mode,
        const std::string& method, double t_end) {
  impactlab::StepperSettings settings;
  settings.rtol = 1e-10;
  settings.atol = 1e-12;
  settings.max_step = system.max_step();
  impactlab::LoopOptions options;
  options.location.grazing_tolerance = settings.atol;
  EventLog log(true);
  const auto simulate_with = [&](auto& stepper) {
    return impactlab::simulate(system, stepper, x0, mode, 0.0, t_end, options, log);
  };
  // the library compiles the loop for the systems its analyses run
  // (analysis/analysis_flows.hpp), and runs an undecorated system's flows as
  // its decorated system's; the loop is compiled here for the undecorated
  // systems alone, so that the two runs compared are two compiled loops
  const auto result = [&] {
    if constexpr (std::is_same_v<System, Variational<LinearImpact>> ||
                  std::is_same_v<System, PendulumWalls>)
      return impactlab::with_stepper<System>(method, settings, simulate_with);
    else
      return impactlab::with_flow<System>(method, settings, simulate_with);
  }();
  EXPECT_EQ(result.termination, impactlab::Termination::completed) << method;
  return {log.records(), std::vector<double>(result.state.begin(), result.state.end())};
}

// exactly equal: the same operations in the same order
void expect_identical(const Run& plain, const Run& decorated, const std::string& context) {
  ASSERT_EQ(plain.events.size(), decorated.events.size()) << context;
  ASSERT_GT(plain.events.size(), 10u) << context;
  for (std::size_t i = 0; i < plain.events.size(); ++i) {
    EXPECT_EQ(plain.events[i].t, decorated.events[i].t) << context << " event " << i;
    EXPECT_EQ(plain.events[i].kind, decorated.events[i].kind) << context << " event " << i;
    EXPECT_EQ(plain.events[i].qdot_after, decorated.events[i].qdot_after) << context;
  }
  EXPECT_EQ(plain.final_state, decorated.final_state) << context;
}

class UndecoratedIsItsBase : public ::testing::TestWithParam<std::string> {};

TEST_P(UndecoratedIsItsBase, PendulumChatteringAndSustainedContact) {
  impactlab::PendulumWallsParameters p;
  p.V0 = 4.163;  // chatter, an accumulation, contact and release
  const PendulumWalls system(p);
  const PendulumWalls::State x0{0.0, 0.1, 0.0};
  const double t_end = 20.0 * 2.0 * 3.141592653589793 / p.omega;
  expect_identical(run(system, x0, PendulumWalls::Mode::free, GetParam(), t_end),
                   run(DecoratedSystem<PendulumWalls>(system), x0, PendulumWalls::Mode::free,
                       GetParam(), t_end),
                   "pendulum " + GetParam());
}

TEST_P(UndecoratedIsItsBase, TangentDynamicsOfTheLinearImpactOscillator) {
  const LinearImpact system(impactlab::LinearImpactParameters{});
  const LinearImpact::State x0{0.0, 0.0};
  const Variational<LinearImpact> plain(system);
  const Variational<DecoratedSystem<LinearImpact>> decorated{DecoratedSystem<LinearImpact>(system)};
  const double t_end = 30.0 * 2.0 * 3.141592653589793 / system.parameters().omega;
  expect_identical(run(plain, plain.start(x0, LinearImpact::Mode::free), LinearImpact::Mode::free,
                       GetParam(), t_end),
                   run(decorated, decorated.start(x0, LinearImpact::Mode::free),
                       LinearImpact::Mode::free, GetParam(), t_end),
                   "linear impact tangent " + GetParam());
}

INSTANTIATE_TEST_SUITE_P(AllSteppers, UndecoratedIsItsBase,
                         ::testing::Values("dopri5", "rkf78", "bulirsch_stoer", "rk8pd", "taylor"));

}  // namespace
