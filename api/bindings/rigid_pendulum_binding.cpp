// The pendulum between walls under the rigid-body model: builds
// RigidPendulumWalls from a scene and runs it through the event loop.
#include <impactlab/api/bindings/rigid_pendulum_binding.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <impactlab/api/bindings/pendulum_walls_parameters.hpp>
#include <impactlab/api/event_tap.hpp>
#include <impactlab/api/run_system.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_walls.hpp>

namespace impactlab {

namespace {

std::string_view mode_name(RigidPendulumWalls::Mode mode) {
  switch (mode) {
    case RigidPendulumWalls::Mode::free: return "free";
    case RigidPendulumWalls::Mode::slide_right_pos: return "slide_right_pos";
    case RigidPendulumWalls::Mode::slide_right_neg: return "slide_right_neg";
    case RigidPendulumWalls::Mode::slide_left_pos: return "slide_left_pos";
    case RigidPendulumWalls::Mode::slide_left_neg: return "slide_left_neg";
    case RigidPendulumWalls::Mode::stick_right: return "stick_right";
    case RigidPendulumWalls::Mode::stick_left: return "stick_left";
  }
  return "unknown";
}

double median(std::vector<double> values) {
  if (values.empty()) return NAN;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

RunOutput run_rigid_pendulum(const Scene& scene, const RunRequest& request) {
  RigidPendulumParameters rp;
  rp.pendulum = pendulum_walls_parameters(scene);
  const PendulumWallsParameters& p = rp.pendulum;
  rp.radius = scene.number("radius");
  rp.spin_free = scene.text("spin") == "free";
  if (!(rp.radius < p.b))
    throw BadInput("radius", to_text(rp.radius), "the ball must fit between the walls (radius < b)");
  if (rp.spin_free && !(rp.radius > 0.0))
    throw BadInput("spin", "free", "a spinning ball needs radius > 0");
  const RigidPendulumWalls system(rp);

  const double theta = scene.number("initial.theta");
  if (std::fabs(theta) > system.wall_angle())
    throw BadInput("initial.theta", to_text(theta),
                   "the ball would start inside a wall (|theta| > asin((b - radius)/l) = " +
                       to_text(system.wall_angle()) + ")");
  const double theta_dot = scene.number("initial.theta_dot");
  // the ball starts without spin of its own: with a free bearing its absolute
  // rate φ̇ is 0, locked it turns with the rod
  const RigidPendulumWalls::State x0{theta, theta_dot, theta, rp.spin_free ? 0.0 : theta_dot, 0.0};
  const double period = 2.0 * std::numbers::pi / p.omega;

  // the tangential restitution that emerges: ρ = γ_T⁺ / γ_T⁻ per impact, and
  // in the paper's convention v_y,a = −e_y v_y0, e_y = −ρ; tallied as the
  // events pass (kept or streamed)
  double friction_work = 0.0;
  std::vector<double> ratios;
  EventTap tally(
      [&](const EventRecord& event) {
        if (event.kind == EventKind::contact_end) friction_work = event.friction_work;
        if (event.kind == EventKind::impact && std::fabs(event.tangential_velocity) > 1e-9)
          ratios.push_back(event.tangential_velocity_after / event.tangential_velocity);
      },
      request.event_sink);
  RunRequest tallied = request;
  tallied.event_sink = &tally;
  RunOutput output =
      run_system(system, x0, RigidPendulumWalls::Mode::free, scene, tallied, period, mode_name);
  const auto [lowest, highest] = std::minmax_element(ratios.begin(), ratios.end());
  output.derived = {
      {"theta0_rad", system.wall_angle()},
      {"ball_inertia_kg_m2", system.ball_inertia()},
      {"spin", rp.spin_free ? "free" : "locked"},
      {"forcing_period_s", period},
      {"friction_work_J", friction_work},
      {"tangential_ratio_impacts", ratios.size()},
      {"tangential_ratio_median", median(ratios)},
      {"tangential_ratio_min", ratios.empty() ? NAN : *lowest},
      {"tangential_ratio_max", ratios.empty() ? NAN : *highest},
      {"emergent_e_t_median", -median(ratios)},
  };
  return output;
}

}  // namespace impactlab
