// Bounded property test over random physical parameter sets, for every
// oscillator and every model, through the registry entry that `impactlab
// simulate` calls. Fixed seed.
//
// Parameters: each numeric physical key drawn within its declared range: a
// key declared on [0, 1] (restitution, friction) uniformly over it, any other
// at its default times 10^u, u uniform in [-0.5, 0.5] (a factor of 3 either
// way), clamped into the declared range. Sets that break a rule between keys
// (b >= l, radius >= b, an initial state past a wall) are refused with
// BadInput naming one of those keys, and counted. Each run: 5 forcing
// periods, sampled 40 times a period.
//
// The promise checked:
// * the run ends `completed`, except where the physics allows a Painlevé
//   stop (painleve_possible below), where it may also end
//   `stopped_by_model` right after a painleve event;
// * a parameter set is refused only by a rule between keys, naming one of
//   its keys;
// * no NaN in any event's time, coordinate or velocities, or in any sample;
// * walls never crossed by more than 1e-9 (in the coordinate's unit) at any
//   sample or event: |θ| <= asin(b/l) for the point-mass pendulum models,
//   x <= σ for the linear impact oscillator, y >= A sin ωt for the ball;
// * energy never increases across an impact (all coefficients are <= 1): the
//   speed relative to the wall does not grow, to 1e-9 relative.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <iostream>
#include <random>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/builtin_scenes.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/system_jobs.hpp>
#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;

// The keys whose rules between keys refuse a parameter set, per oscillator
// (the scene API's BadInput names one of them): b < l, radius < b and a ball
// or bob that starts inside a wall; the linear impact oscillator's exact flow
// also needs ζ < 1.
const std::map<std::string, std::set<std::string>> refusing_keys = {
    {"pendulum_walls", {"b", "radius", "initial.theta"}},
    {"linear_impact", {"initial.x", "zeta"}},
    {"bouncing_ball", {"initial.y"}},
};

// How a run of 5 forcing periods must end (check_run). Every run completes,
// with one exception: the pendulum's contact problem (every model: Newton's impact
// law with Coulomb friction, Model P's sliding impact, the rigid ball at
// radius 0 that reduces to them) divides by cos θ0 − s μ sin θ0 for a slip
// of sign s along the wall, which vanishes or turns negative for s = +1 when
// μ tan θ0 ≥ 1 (θ0 = asin(b/l)): a Painlevé configuration, where the run
// stops (stopped_by_model) after a painleve event. Below that no impact or
// contact can be inconsistent, and nothing else ends a run early at these
// parameters: the accumulation rule closes chatter into contact, the steps
// stay far below limits.max_steps = 1e6, and the states stay bounded.
// Whether a run with μ tan θ0 ≥ 1 meets a slip down the wall within its 5
// periods depends on the motion, so there it may end either way.
bool painleve_possible(const std::string& oscillator, const Scene& scene) {
  if (oscillator != "pendulum_walls") return false;
  const double theta0 = std::asin(scene.number("b") / scene.number("l"));
  // (the contact problem's own margin, contact/painleve.hpp, is 1e-9)
  return scene.number("mu") * std::tan(theta0) >= 1.0 - 1e-6;
}

bool physical_key(const KeySpec& spec) {
  const std::string key(spec.key);
  return !spec.is_text && key != "t0" && key.rfind("integrator.", 0) != 0 &&
         key.rfind("limits.", 0) != 0 && key != "accumulation_tol";
}

double draw(const KeySpec& spec, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double value = 0.0;
  if (spec.lower >= -1.0 && spec.upper <= 1.0)
    value = spec.lower + (spec.upper - spec.lower) * unit(rng);
  else
    value = spec.default_number * std::pow(10.0, unit(rng) - 0.5);
  return std::clamp(value, spec.lower, spec.upper);
}

std::string scene_for(std::string_view oscillator) {
  for (const auto& builtin : builtin_scenes())
    if (load_scene(builtin.name).oscillator == oscillator) return std::string(builtin.name);
  return {};
}

struct Tally {
  int runs = 0, refused = 0, impacts = 0, painleve_possible = 0;
  std::map<std::string, int> terminations;
};

// Checks one run against the promise; `wall_gap(t, q)` >= 0 on the allowed
// side of the wall(s), `wall_velocity(t)` the wall's own velocity.
template <class Gap, class WallVelocity>
void check_run(const RunOutput& output, const std::string& context, bool painleve_possible,
               Gap wall_gap, WallVelocity wall_velocity, bool check_walls, Tally& tally) {
  ++tally.terminations[std::string(to_string(output.termination))];
  const bool painleve_stop = painleve_possible &&
                             output.termination == Termination::stopped_by_model && !output.events.empty() &&
                             output.events.back().kind == EventKind::painleve;
  if (!painleve_stop) {
    EXPECT_EQ(output.termination, Termination::completed) << context << to_string(output.termination);
  }
  for (const auto& event : output.events) {
    EXPECT_TRUE(event.kind != EventKind::painleve || painleve_possible)
        << context << " Painlevé event at t = " << event.t;
  }
  const bool finite_run = output.termination != Termination::non_finite_state;
  for (const auto& event : output.events) {
    const bool numbers_finite = std::isfinite(event.t) && std::isfinite(event.q) &&
                                std::isfinite(event.qdot_before) && std::isfinite(event.qdot_after);
    EXPECT_TRUE(numbers_finite || !finite_run) << context << " event at t = " << event.t;
    if (!numbers_finite) continue;
    if (check_walls) {
      EXPECT_GE(wall_gap(event.t, event.q), -1e-9) << context << " t = " << event.t;
    }
    if (event.kind == EventKind::impact) {
      ++tally.impacts;
      const double wall = wall_velocity(event.t);
      EXPECT_LE(std::fabs(event.qdot_after - wall),
                std::fabs(event.qdot_before - wall) * (1.0 + 1e-9) + 1e-12)
          << context << " impact at t = " << event.t;
    }
  }
  for (const auto& sample : output.samples) {
    EXPECT_TRUE(std::isfinite(sample.q) && std::isfinite(sample.qdot)) << context;
    if (check_walls && std::isfinite(sample.q)) {
      EXPECT_GE(wall_gap(sample.t, sample.q), -1e-9) << context << " sample t = " << sample.t;
    }
  }
}

TEST(OscillatorProperties, RandomPhysicalParametersKeepThePromise) {
  std::mt19937_64 rng(2026);
  Tally tally;
  for (const auto& entry : oscillators()) {
    const std::string oscillator(entry.schema->oscillator);
    const Scene base = load_scene(scene_for(oscillator));
    std::vector<std::string> models = {""};
    if (base.values.contains("model")) {
      models.clear();
      for (const auto& spec : entry.schema->keys)
        if (spec.key == "model")
          for (auto choice : spec.choices) models.emplace_back(choice);
    }
    for (const auto& model : models) {
      for (int k = 0; k < 40; ++k) {
        Scene scene = base;
        std::string context = oscillator + (model.empty() ? "" : " model=" + model);
        try {
          if (!model.empty()) apply_override(scene, "model=" + model);
          for (const auto& spec : entry.schema->keys) {
            if (!physical_key(spec)) continue;
            const double value = draw(spec, rng);
            scene.values[std::string(spec.key)] = value;
            context += " " + std::string(spec.key) + "=" + std::to_string(value);
          }
          apply_override(scene, "limits.max_steps=1e6");  // validates the whole set
          const double omega = scene.number("omega");
          RunRequest request;
          request.periods = 5.0;
          request.sample_step = 2.0 * std::numbers::pi / omega / 40.0;
          const RunOutput output = run_of_scene(scene, request);
          ++tally.runs;
          const bool painleve = painleve_possible(oscillator, scene);
          tally.painleve_possible += painleve;
          if (oscillator == "pendulum_walls") {
            const double wall = std::asin(scene.number("b") / scene.number("l"));
            check_run(output, context, painleve,
                      [wall](double, double q) { return wall - std::fabs(q); },
                      [](double) { return 0.0; }, model != "rigid", tally);
          } else if (oscillator == "linear_impact") {
            const double sigma = scene.number("sigma");
            check_run(output, context, painleve, [sigma](double, double q) { return sigma - q; },
                      [](double) { return 0.0; }, true, tally);
          } else if (oscillator == "bouncing_ball") {
            const double A = scene.number("A");
            check_run(output, context, painleve,
                      [A, omega](double t, double q) { return q - A * std::sin(omega * t); },
                      [A, omega](double t) { return A * omega * std::cos(omega * t); }, true,
                      tally);
          } else {
            ADD_FAILURE() << "no wall geometry in this test for oscillator " << oscillator;
          }
        } catch (const BadInput& bad) {
          ++tally.refused;
          EXPECT_TRUE(refusing_keys.contains(oscillator) &&
                      refusing_keys.at(oscillator).contains(bad.key()))
              << context << ": refused naming " << bad.key() << ": " << bad.what();
        } catch (const std::exception& error) {
          ADD_FAILURE() << context << ": unexpected exception " << error.what();
        }
      }
    }
  }
  EXPECT_GT(tally.runs, 100);
  std::cout << "[ property ] " << tally.runs << " runs, " << tally.refused
            << " parameter sets refused (rules between keys), " << tally.impacts
            << " impacts checked, " << tally.painleve_possible
            << " runs where a Painlevé stop is possible; terminations:";
  for (const auto& [name, count] : tally.terminations) std::cout << " " << name << " " << count;
  std::cout << "\n";
}

}  // namespace
