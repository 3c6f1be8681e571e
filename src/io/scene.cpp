#include <impactlab/io/scene.hpp>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include <impactlab/integrate/stepper_names.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/builtin_scenes.hpp>
#include <impactlab/io/nearest_name.hpp>
#include <impactlab/io/toml_nesting.hpp>

namespace impactlab {

namespace {

const KeySpec* find_key(const SceneSchema& schema, std::string_view key) {
  for (const auto& spec : schema.keys)
    if (spec.key == key) return &spec;
  return nullptr;
}

// what an unknown key's message says after "unknown key for oscillator X":
// the nearest key where one is close, and where every key is listed
std::string unknown_key_hint(const SceneSchema& schema, std::string_view key) {
  std::vector<std::string_view> keys;
  for (const auto& spec : schema.keys) keys.emplace_back(spec.key);
  const auto nearest = nearest_name(key, keys);
  return (nearest ? fmt::format(": did you mean {}?", *nearest) : std::string()) +
         " (impactlab scenes lists every key of each scene)";
}

std::string builtin_names() {
  std::string list;
  for (const auto& scene : builtin_scenes()) {
    if (!list.empty()) list += ", ";
    list += scene.name;
  }
  return list;
}

// A number written on the command line: the whole text must parse, and the
// result must be finite.
double parse_number(const std::string& key, const std::string& text) {
  double value = 0.0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  const auto [end, error] = std::from_chars(first, last, value);
  if (text.empty() || error != std::errc() || end != last)
    throw BadInput(key, text, "not a number");
  if (!std::isfinite(value)) throw BadInput(key, text, "not a finite number");
  return value;
}

// Flattens the TOML document into dotted keys (one level of tables).
void flatten(const toml::table& table, const std::string& prefix,
             std::map<std::string, SceneValue>& out) {
  for (const auto& [raw_key, node] : table) {
    const std::string key = prefix.empty() ? std::string(raw_key.str())
                                           : prefix + "." + std::string(raw_key.str());
    if (const auto* sub = node.as_table()) {
      if (!prefix.empty()) throw BadInput(key, "(table)", "tables nest one level at most");
      flatten(*sub, key, out);
    } else if (const auto* text = node.as_string()) {
      out[key] = text->get();
    } else if (const auto* integer = node.as_integer()) {
      out[key] = static_cast<double>(integer->get());
    } else if (const auto* floating = node.as_floating_point()) {
      out[key] = floating->get();
    } else {
      const std::string shown = node.is_boolean()  ? (node.as_boolean()->get() ? "true" : "false")
                                : node.is_array() ? "(array)"
                                                  : "(date or time)";
      throw BadInput(key, shown, "expected a number or a string");
    }
  }
}

std::string read_scene_text(std::string_view name_or_path) {
  for (const auto& scene : builtin_scenes())
    if (scene.name == name_or_path) return std::string(scene.text);
  const std::filesystem::path path(name_or_path);
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(path, ignored))
    throw BadInput("scene", std::string(name_or_path),
                   "no built-in scene or scene file of that name (built-in: " + builtin_names() +
                       ")");
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw BadInput("scene", std::string(name_or_path), "cannot read the file");
  return text.str();
}

}  // namespace

double Scene::number(const std::string& key) const { return std::get<double>(values.at(key)); }

double Scene::forcing_period() const {
  if (!values.contains("omega"))
    throw BadInput("scene", name, "this scene has no forcing frequency omega to count periods by");
  return 2.0 * std::numbers::pi / number("omega");
}

const std::string& Scene::text(const std::string& key) const {
  return std::get<std::string>(values.at(key));
}

std::string to_text(const SceneValue& value) {
  if (const auto* text = std::get_if<std::string>(&value)) return *text;
  return fmt::format("{}", std::get<double>(value));
}

std::vector<KeySpec> common_keys() {
  std::vector<std::string_view> methods(stepper_names.begin(), stepper_names.end());
  std::vector<std::string_view> classification_methods{"same"};
  classification_methods.insert(classification_methods.end(), methods.begin(), methods.end());
  return {
      {.key = "name", .help = "scene name", .is_text = true, .default_text = ""},
      {.key = "description", .help = "what the scene is", .is_text = true, .default_text = ""},
      {.key = "t0", .unit = "s", .help = "start time", .default_number = 0.0},
      {.key = "integrator.method",
       .help = "dense-output stepper, or the closed-form flow",
       .is_text = true,
       .default_text = "dopri5",
       .choices = methods},
      {.key = "integrator.rtol", .help = "relative tolerance per step", .default_number = 1e-10,
       .lower = 0.0, .upper = 1.0, .lower_open = true},
      {.key = "integrator.atol", .unit = "state units", .help = "absolute tolerance per step",
       .default_number = 1e-12, .lower = 0.0, .upper = 1.0, .lower_open = true},
      // a sweep that only classifies (a 2D map) integrates at these instead of
      // the three above where the scene states them (classification_rtol > 0);
      // chosen per scene from data (docs/performance.md, "Classification
      // tolerance"), so a scene without them keeps its own integrator
      {.key = "integrator.classification_method",
       .help = "stepper of a classification-only sweep (2D map); same: integrator.method",
       .is_text = true,
       .default_text = "same",
       .choices = classification_methods},
      {.key = "integrator.classification_rtol",
       .help = "relative tolerance per step of a classification-only sweep; 0: none stated "
               "(the sweep keeps integrator.rtol)",
       .default_number = 0.0, .lower = 0.0, .upper = 1.0},
      {.key = "integrator.classification_atol", .unit = "state units",
       .help = "absolute tolerance per step of a classification-only sweep; 0: none stated "
               "(the sweep keeps integrator.atol)",
       .default_number = 0.0, .lower = 0.0, .upper = 1.0},
      {.key = "limits.max_steps",
       .help = "step budget of one run: refused up front when it needs more, else stops "
               "(step_budget) when it takes more",
       .default_number = static_cast<double>(default_scene_step_budget), .lower = 1.0,
       .upper = 1e15},
      {.key = "limits.max_rows",
       .help = "most rows a sampled output (trajectory.csv) or a sweep's grid may have; "
               "refused up front beyond",
       .default_number = static_cast<double>(default_scene_row_budget), .lower = 1.0,
       .upper = 1e12},
  };
}

KeySpec accumulation_tolerance_key() {
  return {.key = "accumulation_tol",
          .help = "accepted error of an accumulation (chattering) time, relative to the time "
                  "scale 1/omega; 0: the integrator's rtol",
          .default_number = 0.0, .lower = 0.0, .upper = 0.5};
}

AccumulationTolerance accumulation_tolerance(const Scene& scene, double time_scale,
                                             double wall_coordinate,
                                             double normal_per_coordinate) {
  const double rtol = scene.number("integrator.rtol");
  const double atol = scene.number("integrator.atol");
  const double relative = scene.number("accumulation_tol");
  return {.time = (relative > 0.0 ? relative : rtol) * time_scale,
          .unresolved_apex =
              (atol + rtol * std::fabs(wall_coordinate)) * normal_per_coordinate,
          .gap_roundoff = 4.0 * std::numeric_limits<double>::epsilon() *
                          std::fabs(wall_coordinate) * normal_per_coordinate};
}

double accumulation_time_tolerance(const Scene& scene) {
  if (!scene.values.contains("accumulation_tol") || !scene.values.contains("omega"))
    return std::numeric_limits<double>::quiet_NaN();
  return accumulation_tolerance(scene, 1.0 / scene.number("omega"), 0.0).time;
}

void validate(const Scene& scene, const SceneSchema& schema) {
  for (const auto& [key, value] : scene.values) {
    const KeySpec* spec = find_key(schema, key);
    if (!spec)
      throw BadInput(key, to_text(value), fmt::format("unknown key for oscillator {}{}",
                                                      schema.oscillator,
                                                      unknown_key_hint(schema, key)));
    if (spec->is_text) {
      const auto* text = std::get_if<std::string>(&value);
      if (!text) throw BadInput(key, to_text(value), "expected text");
      if (!spec->choices.empty()) {
        bool allowed = false;
        std::string listed;
        for (auto choice : spec->choices) {
          allowed = allowed || choice == *text;
          listed += (listed.empty() ? "" : ", ") + std::string(choice);
        }
        if (!allowed) throw BadInput(key, *text, "expected one of: " + listed);
      }
      continue;
    }
    const auto* number = std::get_if<double>(&value);
    if (!number) throw BadInput(key, to_text(value), "expected a number");
    if (!std::isfinite(*number)) throw BadInput(key, to_text(value), "not a finite number");
    const bool below = spec->lower_open ? !(*number > spec->lower) : !(*number >= spec->lower);
    const bool above = spec->upper_open ? !(*number < spec->upper) : !(*number <= spec->upper);
    if (below || above) throw BadInput(key, to_text(value), "out of range " + range_text(*spec));
  }
}

std::string scene_file_description(const std::filesystem::path& path) {
  try {
    const toml::table file = toml::parse_file(path.string());
    return file["description"].value_or(std::string());
  } catch (const toml::parse_error&) {
    return {};
  }
}

std::string range_text(const KeySpec& spec) {
  return fmt::format("{}{}, {}{}", spec.lower_open ? "(" : "[",
                     spec.lower <= -1e308 ? "-inf" : to_text(spec.lower),
                     spec.upper >= 1e308 ? "inf" : to_text(spec.upper),
                     spec.upper_open ? ")" : "]");
}

std::string model_oscillator_name(std::string_view path) { return "model:" + std::string(path); }

Scene read_scene(std::string_view name_or_path, const SchemaLookup& schema_of) {
  const std::string text = read_scene_text(name_or_path);
  std::map<std::string, SceneValue> values;
  try {
    toml::table document = parse_bounded_toml(text, std::string(name_or_path));
    // a [model] section defines the scene's oscillator (oscillators/model_file/;
    // the scene API registers it under model_oscillator_name before the read)
    if (document["model"].is_table()) {
      values["oscillator"] = model_oscillator_name(name_or_path);
      document.erase("model");
      if (document.contains("oscillator"))
        throw BadInput("oscillator", "(given)", "a scene with a [model] section defines its own oscillator");
    }
    flatten(document, "", values);
  } catch (const toml::parse_error& error) {
    throw BadInput("scene", std::string(name_or_path),
                   fmt::format("malformed TOML at line {}: {}", error.source().begin.line,
                               error.description()));
  }
  const auto oscillator = values.find("oscillator");
  if (oscillator == values.end())
    throw BadInput("oscillator", "(missing)", "a scene must name its oscillator");
  const std::string oscillator_name = to_text(oscillator->second);
  values.erase(oscillator);
  const SceneSchema& schema = schema_of(oscillator_name);

  Scene scene{std::string(name_or_path), oscillator_name, std::move(values)};
  validate(scene, schema);
  for (const auto& spec : schema.keys) {
    if (scene.values.contains(std::string(spec.key))) continue;
    if (spec.is_text)
      scene.values[std::string(spec.key)] = std::string(spec.default_text);
    else
      scene.values[std::string(spec.key)] = spec.default_number;
  }
  return scene;
}

void set_scene_key(Scene& scene, const SceneSchema& schema, std::string_view assignment) {
  const auto equals = assignment.find('=');
  if (equals == std::string_view::npos || equals == 0)
    throw BadInput("set", std::string(assignment), "expected KEY=VALUE");
  const std::string key(assignment.substr(0, equals));
  const std::string text(assignment.substr(equals + 1));
  const KeySpec* spec = find_key(schema, key);
  if (!spec)
    throw BadInput(key, text, fmt::format("unknown key for oscillator {}{}", schema.oscillator,
                                          unknown_key_hint(schema, key)));
  if (spec->is_text)
    scene.values[key] = text;
  else
    scene.values[key] = parse_number(key, text);
  validate(scene, schema);
  scene.assigned.insert(key);
}

}  // namespace impactlab
