#include <impactlab/oscillators/model_file/model_definition.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <set>

#include <fmt/format.h>

#include <impactlab/io/toml_nesting.hpp>

namespace impactlab {

namespace {

SourcePosition position_of(const toml::source_region& region, const std::string& file) {
  return {file, static_cast<std::uint32_t>(region.begin.line),
          static_cast<std::uint32_t>(region.begin.column)};
}

// Reads one table of the section, checking that it names only known keys.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string path, const std::string& file)
      : table_(table), path_(std::move(path)), file_(file) {}

  [[nodiscard]] SourcePosition where() const { return position_of(table_.source(), file_); }
  [[nodiscard]] std::string key(std::string_view name) const {
    return path_ + "." + std::string(name);
  }
  [[nodiscard]] const toml::node* find(std::string_view name) const { return table_.get(name); }

  [[noreturn]] void fail_at(const toml::node& node, std::string_view name,
                            const std::string& message) const {
    throw ModelFileError(position_of(node.source(), file_), key(name), message);
  }
  [[noreturn]] void fail_missing(std::string_view name, const std::string& message) const {
    throw ModelFileError(where(), key(name), message);
  }

  void only_keys(std::initializer_list<std::string_view> allowed) const {
    for (const auto& [name, node] : table_) {
      if (std::find(allowed.begin(), allowed.end(), name.str()) != allowed.end()) continue;
      std::string listed;
      for (auto known : allowed) listed += (listed.empty() ? "" : ", ") + std::string(known);
      throw ModelFileError(position_of(name.source(), file_), key(name.str()),
                           "unknown key '" + key(name.str()) + "' (known in " + path_ + ": " +
                               listed + ")");
    }
  }

  // An expression: a string (its first character is one past the quote) or a number.
  [[nodiscard]] ExpressionText expression(const toml::node& node, std::string_view name) const {
    SourcePosition at = position_of(node.source(), file_);
    if (const auto* text = node.as_string()) {
      const bool multiline = node.source().end.line != node.source().begin.line;
      return {key(name), text->get(), multiline ? at : at.advanced(1)};
    }
    if (const auto* integer = node.as_integer())
      return {key(name), std::to_string(integer->get()), at};
    if (const auto* floating = node.as_floating_point()) {
      if (!std::isfinite(floating->get())) fail_at(node, name, "not a finite number");
      return {key(name), fmt::format("{}", floating->get()), at};
    }
    fail_at(node, name, "expected an expression (a string such as \"A*cos(omega*t)\")");
  }
  [[nodiscard]] ExpressionText required_expression(std::string_view name,
                                                   const std::string& what) const {
    const toml::node* node = find(name);
    if (!node) fail_missing(name, path_ + " has no " + std::string(name) + " (" + what + ")");
    return expression(*node, name);
  }
  [[nodiscard]] std::string required_name(std::string_view name, const std::string& what) const {
    const toml::node* node = find(name);
    if (!node) fail_missing(name, path_ + " has no " + std::string(name) + " (" + what + ")");
    if (!node->is_string()) fail_at(*node, name, "expected a name in quotes (" + what + ")");
    return node->as_string()->get();
  }
  [[nodiscard]] const toml::table& subtable(const toml::node& node, std::string_view name) const {
    if (!node.is_table()) fail_at(node, name, "expected a table");
    return *node.as_table();
  }
  [[nodiscard]] StateExpressions expressions(const toml::table& table, const std::string& path) const {
    StateExpressions out;
    for (const auto& [name, node] : table) {
      TableReader inner(table, path, file_);
      ExpressionText text = inner.expression(node, name.str());
      out.emplace_back(std::string(name.str()), std::move(text));
    }
    return out;
  }
  [[nodiscard]] SourcePosition key_position(std::string_view name) const {
    for (const auto& [key, node] : table_)
      if (key.str() == name) return position_of(key.source(), file_);
    return where();
  }

 private:
  const toml::table& table_;
  std::string path_;
  const std::string& file_;
};

void check_name(const std::string& name, const SourcePosition& where, const std::string& key) {
  const bool valid = !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                     std::all_of(name.begin(), name.end(), [](char c) {
                       return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                     });
  if (!valid) throw ModelFileError(where, key, "'" + name + "' is not a name (letters, digits, _)");
  if (is_reserved_name(name))
    throw ModelFileError(where, key, "'" + name + "' is reserved (a function, pi or the time t)");
}

std::vector<std::string> read_states(const TableReader& model, const std::string& file,
                                     SourcePosition& where) {
  const toml::node* node = model.find("states");
  if (!node) model.fail_missing("states", "[model] has no states (e.g. states = [\"x\", \"v\"])");
  where = position_of(node->source(), file);
  const auto* array = node->as_array();
  if (!array || array->empty()) model.fail_at(*node, "states", "expected a list of state names");
  std::vector<std::string> states;
  for (const auto& element : *array) {
    const SourcePosition at = position_of(element.source(), file);
    if (!element.is_string()) throw ModelFileError(at, "model.states", "expected a name in quotes");
    const std::string name = element.as_string()->get();
    check_name(name, at.advanced(1), "model.states");
    if (std::find(states.begin(), states.end(), name) != states.end())
      throw ModelFileError(at.advanced(1), "model.states", "state '" + name + "' listed twice");
    states.push_back(name);
  }
  if (states.size() % 2 != 0 || states.size() > 8)
    model.fail_at(*node, "states",
                  fmt::format("{} states: list positions and velocities in pairs, 2 or 4 in all "
                              "(this build compiles 1- and 2-degree-of-freedom models)",
                              states.size()));
  if (states.size() != 2 && states.size() != 4)
    model.fail_at(*node, "states", fmt::format("{} states: this build runs 2 or 4", states.size()));
  return states;
}

ModelParameter read_parameter(const std::string& name, const toml::node& node,
                              const std::string& file) {
  ModelParameter parameter;
  parameter.name = name;
  parameter.position = position_of(node.source(), file);
  const std::string key = "model.parameters." + name;
  auto number = [&](const toml::node& value, const std::string& what) {
    if (const auto* integer = value.as_integer()) return static_cast<double>(integer->get());
    if (const auto* floating = value.as_floating_point()) {
      if (std::isfinite(floating->get())) return floating->get();
    }
    throw ModelFileError(position_of(value.source(), file), key, what + " must be a finite number");
  };
  if (!node.is_table()) {
    parameter.default_value = number(node, "a parameter's default");
    return parameter;
  }
  const toml::table& table = *node.as_table();
  TableReader reader(table, key, file);
  reader.only_keys({"default", "min", "max", "min_open", "max_open", "unit", "help"});
  const toml::node* default_node = reader.find("default");
  if (!default_node) reader.fail_missing("default", "a parameter needs a default");
  parameter.default_value = number(*default_node, "default");
  if (const auto* lower = reader.find("min")) parameter.lower = number(*lower, "min");
  if (const auto* upper = reader.find("max")) parameter.upper = number(*upper, "max");
  auto flag = [&](std::string_view flag_name) {
    const toml::node* value = reader.find(flag_name);
    if (!value) return false;
    if (!value->is_boolean()) reader.fail_at(*value, flag_name, "expected true or false");
    return value->as_boolean()->get();
  };
  parameter.lower_open = flag("min_open");
  parameter.upper_open = flag("max_open");
  auto text = [&](std::string_view text_name) {
    const toml::node* value = reader.find(text_name);
    if (!value) return std::string();
    if (!value->is_string()) reader.fail_at(*value, text_name, "expected text in quotes");
    return value->as_string()->get();
  };
  parameter.unit = text("unit");
  parameter.help = text("help");
  const double v = parameter.default_value;
  const bool below = parameter.lower_open ? !(v > parameter.lower) : !(v >= parameter.lower);
  const bool above = parameter.upper_open ? !(v < parameter.upper) : !(v <= parameter.upper);
  if (below || above)
    throw ModelFileError(position_of(default_node->source(), file), key,
                         fmt::format("default {} is outside its range", v));
  return parameter;
}

// Every state has exactly one expression (complete = true), or a subset of them.
void check_states(const StateExpressions& expressions, const std::vector<std::string>& states,
                  bool complete, const SourcePosition& table_where, const std::string& path) {
  for (const auto& [name, text] : expressions)
    if (std::find(states.begin(), states.end(), name) == states.end())
      throw ModelFileError(text.position, path + "." + name,
                           fmt::format("'{}' is not a state (dimension mismatch: states are {})",
                                       name, fmt::join(states, ", ")));
  if (!complete) return;
  for (const auto& state : states) {
    const bool present = std::any_of(expressions.begin(), expressions.end(),
                                     [&](const auto& entry) { return entry.first == state; });
    if (!present)
      throw ModelFileError(table_where, path,
                           fmt::format("no equation for state '{}' (dimension mismatch: {} states, "
                                       "{} equations)",
                                       state, states.size(), expressions.size()));
  }
}

// The expressions reordered to the order of the states.
StateExpressions in_state_order(const StateExpressions& expressions,
                                const std::vector<std::string>& states) {
  StateExpressions ordered;
  for (const auto& state : states)
    for (const auto& entry : expressions)
      if (entry.first == state) ordered.push_back(entry);
  return ordered;
}

ModelReset read_reset(const TableReader& wall, const std::string& wall_path,
                      const ModelDefinition& model, const std::string& file) {
  const toml::node* node = wall.find("reset");
  if (!node)
    wall.fail_missing("reset",
                      "missing reset: a wall needs reset = { velocity = \"v\", restitution = \"r\" } "
                      "or reset = { map = { ... } }");
  const toml::table& table = wall.subtable(*node, "reset");
  const std::string path = wall_path + ".reset";
  TableReader reader(table, path, file);
  ModelReset reset;
  reset.where = position_of(node->source(), file);
  if (const toml::node* map = reader.find("map")) {
    reader.only_keys({"map"});
    reset.kind = ModelReset::Kind::map;
    const toml::table& map_table = reader.subtable(*map, "map");
    reset.map = reader.expressions(map_table, path + ".map");
    check_states(reset.map, model.states, false, reset.where, path + ".map");
    if (reset.map.empty()) reader.fail_at(*map, "map", "a reset map changes at least one state");
    return reset;
  }
  reader.only_keys({"velocity", "restitution", "position"});
  reset.kind = ModelReset::Kind::newton;
  reset.velocity = reader.required_name("velocity", "the state whose value the impact changes");
  reset.restitution = reader.required_expression("restitution", "the coefficient of restitution");
  if (reader.find("position")) reset.position = reader.required_name("position", "");
  for (const std::string* name : {&reset.velocity, &reset.position}) {
    if (name->empty()) continue;
    if (std::find(model.states.begin(), model.states.end(), *name) == model.states.end())
      throw ModelFileError(reset.where, path, "'" + *name + "' is not a state");
  }
  return reset;
}

ModelSticking read_sticking(const toml::node& node, const std::string& wall_path,
                            const ModelDefinition& model, const std::string& file,
                            const TableReader& wall) {
  const toml::table& table = wall.subtable(node, "sticking");
  const std::string path = wall_path + ".sticking";
  TableReader reader(table, path, file);
  reader.only_keys({"rhs", "state", "force", "gap_scale"});
  ModelSticking sticking;
  sticking.where = position_of(node.source(), file);
  for (auto [name, target] : {std::pair{"rhs", &sticking.rhs}, std::pair{"state", &sticking.state}}) {
    const toml::node* entry = reader.find(name);
    if (!entry)
      reader.fail_missing(name, std::string("a sticking mode needs its ") +
                                    (target == &sticking.rhs ? "vector field rhs" : "state on the wall"));
    *target = reader.expressions(reader.subtable(*entry, name), path + "." + name);
    check_states(*target, model.states, true, position_of(entry->source(), file), path + "." + name);
    *target = in_state_order(*target, model.states);
  }
  sticking.force = reader.required_expression("force", "the push into the wall; contact ends where it falls to zero");
  if (reader.find("gap_scale"))
    sticking.gap_scale = reader.required_expression("gap_scale", "the size of the gap's terms");
  return sticking;
}

ModelWall read_wall(const toml::table& table, std::size_t index, const ModelDefinition& model,
                    const std::string& file) {
  const std::string path = fmt::format("model.walls[{}]", index);
  TableReader reader(table, path, file);
  reader.only_keys({"name", "side", "witness", "direction", "reset", "sticking"});
  ModelWall wall;
  wall.where = reader.where();
  wall.name = reader.find("name") ? reader.required_name("name", "") : fmt::format("wall{}", index);
  if (const toml::node* side = reader.find("side")) {
    if (!side->is_integer() || std::abs(side->as_integer()->get()) != 1)
      reader.fail_at(*side, "side", "expected +1 or -1 (the wall's sign in events.csv)");
    wall.side = static_cast<int>(side->as_integer()->get());
  }
  wall.witness = reader.required_expression("witness", "the signed gap to the wall");
  const toml::node* direction = reader.find("direction");
  if (!direction)
    reader.fail_missing("direction",
                        "witness without direction: give direction = \"falling\" (the gap closes "
                        "through zero) or \"rising\"");
  const std::string text = direction->is_string() ? direction->as_string()->get() : "";
  if (text == "falling") wall.direction = TriggerDirection::falling;
  else if (text == "rising") wall.direction = TriggerDirection::rising;
  else reader.fail_at(*direction, "direction", "expected \"falling\" or \"rising\"");
  wall.reset = read_reset(reader, path, model, file);
  if (const toml::node* sticking = reader.find("sticking")) {
    if (wall.reset.kind != ModelReset::Kind::newton)
      reader.fail_at(*sticking, "sticking",
                     "a sticking mode needs a Newton reset (its restitution sets how impacts accumulate)");
    wall.has_sticking = true;
    wall.sticking = read_sticking(*sticking, path, model, file, reader);
  }
  return wall;
}

}  // namespace

ModelDefinition read_model_definition(const toml::table& section, const std::string& file) {
  ModelDefinition model;
  model.file = file;
  TableReader reader(section, "model", file);
  reader.only_keys({"states", "parameters", "definitions", "rhs", "walls", "forcing_frequency",
                    "max_step"});
  model.states = read_states(reader, file, model.states_where);

  std::set<std::string> taken(model.states.begin(), model.states.end());
  auto claim = [&](const std::string& name, const SourcePosition& where, const std::string& key) {
    check_name(name, where, key);
    if (!taken.insert(name).second)
      throw ModelFileError(where, key, "'" + name + "' is already a state, parameter or definition");
  };
  if (const toml::node* node = reader.find("parameters")) {
    const toml::table& table = reader.subtable(*node, "parameters");
    for (const auto& [name, value] : table) {
      claim(std::string(name.str()), position_of(name.source(), file),
            "model.parameters." + std::string(name.str()));
      model.parameters.push_back(read_parameter(std::string(name.str()), value, file));
    }
  }
  if (const toml::node* node = reader.find("definitions")) {
    model.definitions = reader.expressions(reader.subtable(*node, "definitions"), "model.definitions");
    for (const auto& [name, text] : model.definitions) claim(name, text.position, text.key);
  }

  const toml::node* rhs = reader.find("rhs");
  if (!rhs) reader.fail_missing("rhs", "[model] has no rhs (one equation per state)");
  model.rhs_where = position_of(rhs->source(), file);
  model.rhs = reader.expressions(reader.subtable(*rhs, "rhs"), "model.rhs");
  check_states(model.rhs, model.states, true, model.rhs_where, "model.rhs");
  model.rhs = in_state_order(model.rhs, model.states);

  model.forcing_frequency =
      reader.required_expression("forcing_frequency", "ω, the forcing frequency (rad per time unit)");
  if (const toml::node* node = reader.find("max_step")) model.max_step = reader.expression(*node, "max_step");

  if (const toml::node* walls = reader.find("walls")) {
    const auto* array = walls->as_array();
    if (!array || !array->is_array_of_tables())
      reader.fail_at(*walls, "walls", "expected [[model.walls]] tables");
    for (std::size_t k = 0; k < array->size(); ++k)
      model.walls.push_back(read_wall(*array->get(k)->as_table(), k, model, file));
    if (model.walls.size() > 6) reader.fail_at(*walls, "walls", "at most 6 walls");
  }
  return model;
}

ModelDefinition read_model_file(const std::string& path) {
  toml::table scene;
  try {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    if (!in) throw ModelFileError({path, 1, 1}, "scene", "cannot read the file");
    scene = parse_bounded_toml(text.str(), path);
  } catch (const toml::parse_error& error) {
    throw ModelFileError(position_of(error.source(), path), "scene",
                         "malformed TOML: " + std::string(error.description()));
  }
  const toml::node* model = scene.get("model");
  if (!model || !model->is_table())
    throw ModelFileError({path, 1, 1}, "model", "the scene file has no [model] section");
  return read_model_definition(*model->as_table(), path);
}

bool has_model_section(const toml::table& scene) {
  const toml::node* model = scene.get("model");
  return model && model->is_table();
}

}  // namespace impactlab
