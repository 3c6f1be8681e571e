// The same scene under several impact models, side by side:
// runs the scene once per model by overriding its `model` key, keeps the
// impacts, the contact intervals and the stroboscopic section points
// (t = t0 + k T, T = 2π/ω) of each run, matches the impacts by their order,
// and writes the tables and a summary whose numbers are all computed here.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

// One sustained-contact interval of a run: contact_start .. contact_end (or
// the end of the run).
struct ContactInterval {
  int wall = 0;
  double t_start = 0.0, t_end = 0.0;  // s
  double friction_work = 0.0;         // J, friction work over the interval
};

struct ModelRun {
  std::string model;
  Scene scene;        // the scene as run (model overridden)
  RunOutput output;   // events and the strobe samples
  std::vector<EventRecord> impacts;
  std::vector<ContactInterval> contacts;
};

struct Comparison {
  double period = 0.0;  // forcing period T (s) of the strobe section
  std::vector<ModelRun> runs;
};

// "newton,rigid" -> {"newton", "rigid"}; BadInput (key `models`) on an empty
// or repeated name. The names themselves are checked by the scene.
std::vector<std::string> parse_model_list(std::string_view list);

// The choices of the scene's `model` key (empty if it has none).
std::vector<std::string> scene_models(const Scene& scene);

// The models to compare: those of `list` ("newton,rigid"), or where it is
// empty every model the scene accepts (each tried on a tiny run; `skipped`
// hears why one is not). BadInput (key `oscillator`) for a scene without a
// `model` key, (key `models`) when none is accepted.
std::vector<std::string> models_to_compare(const Scene& scene, const std::string& list,
                                           const std::function<void(const BadInput&)>& skipped);

// Runs every model; BadInput from the scene (an unknown or unavailable model,
// keys that do not fit the model) is passed on before anything is written.
// request.sample_step is replaced by the forcing period 2π/ω.
Comparison compare_models(const Scene& scene, const std::vector<std::string>& models,
                          RunRequest request);

// Impacts matched by order: k, then for each model t, wall, qdot_before,
// qdot_after, normal_impulse, tangential_velocity, tangential_velocity_after
// (columns suffixed _<model>; empty past a model's last impact).
void write_impacts_csv(std::ostream& out, const Comparison& comparison);
// model, k, wall, t_start, t_end, duration, friction_work
void write_contacts_csv(std::ostream& out, const Comparison& comparison);
// k, t, then q_<model>, qdot_<model> at each strobe time
void write_section_csv(std::ostream& out, const Comparison& comparison);

// Per model and per pair (each model against the first), the numbers the
// summary quotes: counts, agreement of the impact sequences, section distance.
nlohmann::json comparison_numbers(const Comparison& comparison);

// summary.md: where the models agree and why they differ, from the numbers.
std::string comparison_summary(const Comparison& comparison, const nlohmann::json& numbers);

}  // namespace impactlab
