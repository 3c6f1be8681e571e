// Scenes: which oscillator, which model, its parameters, initial state and
// integrator, read from a TOML scene file (or a built-in one) and changed by
// `--set KEY=VALUE`. Every key is declared once in its oscillator's schema,
// with default, range, unit and help; that table drives validation, the
// `scenes` listing and the meta.json record.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <impactlab/contact/accumulation.hpp>

namespace impactlab {

// One declared scene key. Numbers have a range; text has a list of choices.
struct KeySpec {
  std::string_view key;            // bare (omega) or dotted (initial.theta)
  std::string_view unit;           // "rad/s", "" for dimensionless or text
  std::string_view help;
  bool is_text = false;
  double default_number = 0.0;
  double lower = -1e308, upper = 1e308;  // admissible range
  bool lower_open = false, upper_open = false;  // exclude the bound itself
  std::string_view default_text{};
  std::vector<std::string_view> choices{};
  // the values of the schema's selector key (SceneSchema::selector) whose
  // model reads this key, where only some do (the pendulum's e_t: {"paper"});
  // empty: every model reads it
  std::vector<std::string_view> read_by{};
};

// A number key's range as the messages and `scenes` write it: "(0, inf]",
// "[-1, 0]" (a bound at ±1e308 is none, written ±inf).
std::string range_text(const KeySpec& spec);

struct SceneSchema {
  std::string_view oscillator;
  std::string_view main_coordinate;  // q in events.csv: "theta", "x", "y"
  std::vector<KeySpec> keys;
  // the text key whose value picks the model that runs the scene ("model"),
  // in a schema where some keys are read by some models only (KeySpec::read_by);
  // empty: one model reads every key
  std::string_view selector{};
};

using SceneValue = std::variant<double, std::string>;

struct Scene {
  std::string name;        // built-in name or file path
  std::string oscillator;  // schema it follows
  std::map<std::string, SceneValue> values;  // every key of the schema, resolved
  // the keys given by an assignment (--set, a Python keyword) rather than by
  // the scene file or a default: a sweep's classification tolerance yields to
  // an integrator key the user set (analysis/sweep.hpp)
  std::set<std::string> assigned;

  [[nodiscard]] double number(const std::string& key) const;
  [[nodiscard]] const std::string& text(const std::string& key) const;
  // 2π/ω, the forcing period runs and views count in (s); BadInput where
  // the scene has no forcing frequency omega
  [[nodiscard]] double forcing_period() const;
};

// Default resource limits of a run (scene keys limits.max_steps and
// limits.max_rows): 10^8 steps is a few minutes of CPU time for the built-in
// scenes (docs/simulation.md, "Resource limits"); 10^7 rows of trajectory.csv
// is about 0.5 GB of text.
constexpr std::uint64_t default_scene_step_budget = 100'000'000;
constexpr std::uint64_t default_scene_row_budget = 10'000'000;

// Keys every oscillator accepts (integrator, start time, resource limits),
// merged into each oscillator's schema.
std::vector<KeySpec> common_keys();

// `accumulation_tol`, the key of every oscillator whose impacts can
// accumulate (src/contact/accumulation.hpp).
KeySpec accumulation_tolerance_key();

// What an accumulation estimate of a validated scene is held to
// (contact/accumulation.hpp): the error of its time to accumulation_tol ×
// time_scale (s), or, when accumulation_tol is 0 (its default), to
// integrator.rtol × time_scale, the standard the impacts are held to. The
// chatter counts as unresolvable once a flight's apex is within the
// integrator's accuracy on the gap, (atol + rtol |wall_coordinate|) ×
// normal_per_coordinate (the normal gap per unit of the coordinate: m/rad
// for the pendulum's angle, 1 where the coordinate is the gap's own), and
// the gap's round-off is 4 ulps of the wall coordinate.
AccumulationTolerance accumulation_tolerance(const Scene& scene, double time_scale,
                                             double wall_coordinate,
                                             double normal_per_coordinate = 1.0);

// The accepted error of an accumulation time (s) of a scene whose time scale
// is 1/omega, for meta.json; NaN for a scene without accumulation_tol or omega.
double accumulation_time_tolerance(const Scene& scene);

// The schema of an oscillator by name; the scene API's registry supplies it
// (api/scene_loading.hpp), so that reading a scene knows no oscillator.
using SchemaLookup = std::function<const SceneSchema&(std::string_view oscillator)>;

// The name of the oscillator a scene file's [model] section defines.
std::string model_oscillator_name(std::string_view path);

// A scene file's top-level `description`, without reading its model (no
// compile); empty where it has none or cannot be read.
std::string scene_file_description(const std::filesystem::path& path);

// Reads a built-in scene by name or a scene file by path, fills defaults from
// the schema of the oscillator it names (or its [model] section defines), and validates every key and value.
// Throws BadInput.
Scene read_scene(std::string_view name_or_path, const SchemaLookup& schema_of);

// Applies `KEY=VALUE` (repeatable --set) and validates again. Throws BadInput.
void set_scene_key(Scene& scene, const SceneSchema& schema, std::string_view assignment);

// Checks every value against the schema's ranges and choices. Throws BadInput.
void validate(const Scene& scene, const SceneSchema& schema);

// The value as text, for error messages and listings.
std::string to_text(const SceneValue& value);

}  // namespace impactlab
