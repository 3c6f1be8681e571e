// The `[model]` section of a scene file, as written: names the user chose,
// expressions as text with their positions in the file. No mathematics here;
// oscillators/model_file/symbolic_model.hpp turns it into expressions.
//
// Schema (docs/extending.md has a worked example):
//     [model]
//     states = ["x", "v"]            positions and their velocities, in pairs;
//                                    the first pair is events.csv's q, qdot
//     forcing_frequency = "omega"    ω (rad per time unit): periods, strobe sections
//     max_step = "2*pi/omega/16"     optional; largest integrator step (time)
//     [model.parameters]             become scene keys (and --set keys)
//     omega = { default = 2.0, min = 0.0, min_open = true, unit = "1/time", help = "..." }
//     g = 9.81                       a bare number is a parameter with that default
//     [model.definitions]            optional named subexpressions (no cycles)
//     [model.rhs]                    one equation per state: d(state)/dt
//     [[model.walls]]                one table per wall (a witness with its reset)
//     name, side (+1 / -1: events.csv's wall), witness (a gap, falling to zero),
//     direction ("falling" | "rising"), reset = { velocity, restitution[, position] }
//     or reset = { map = { state = "expression", ... } },
//     sticking = { rhs = {...}, state = {...}, force = "..."[, gap_scale = "..."] } (optional)
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/oscillators/model_file/model_expression.hpp>

namespace impactlab {

// A model parameter: a scene key with default, range, unit and help.
struct ModelParameter {
  std::string name;
  double default_value = 0.0;
  double lower = -1e308, upper = 1e308;
  bool lower_open = false, upper_open = false;
  std::string unit, help;
  SourcePosition position;
};

// Expressions per state name (a right-hand side, a reset map, a sticking state).
using StateExpressions = std::vector<std::pair<std::string, ExpressionText>>;

// What happens at a wall's impact.
struct ModelReset {
  enum class Kind {
    newton,  // Newton's law on the witness's rate, solved for a named velocity
    map,     // a general map: the listed states get new values, the others keep theirs
  };
  Kind kind = Kind::newton;
  std::string velocity;          // newton: the state the impulse changes
  ExpressionText restitution;    // newton: r in [0, 1]: ḣ⁺ = −r ḣ⁻
  std::string position;          // newton, optional: a state put back on the wall
  StateExpressions map;          // map: state -> value after the impact
  SourcePosition where;
};

// The optional sticking mode of a wall: the state rests on it after an
// accumulation of impacts, moving with `rhs`, until `force` falls to zero.
struct ModelSticking {
  StateExpressions rhs;    // the vector field while stuck
  StateExpressions state;  // the state on the wall (entering and leaving the mode)
  ExpressionText force;    // the push into the wall per unit mass (> 0 keeps contact)
  // optional: the size of the terms the gap is computed from (wall coordinate
  // units); the gap's round-off, below which a chatter cannot be resolved, is
  // 4 ulps of it (contact/accumulation.hpp's ρ). Empty: not given.
  ExpressionText gap_scale;
  SourcePosition where;
};

struct ModelWall {
  std::string name;
  int side = 1;  // events.csv's wall column
  ExpressionText witness;
  TriggerDirection direction = TriggerDirection::falling;
  ModelReset reset;
  bool has_sticking = false;
  ModelSticking sticking;
  SourcePosition where;
};

struct ModelDefinition {
  std::string file;
  std::vector<std::string> states;
  SourcePosition states_where;
  std::vector<ModelParameter> parameters;
  StateExpressions definitions;  // name -> expression
  StateExpressions rhs;          // state -> d(state)/dt, in the order of `states`
  SourcePosition rhs_where;
  std::vector<ModelWall> walls;
  ExpressionText forcing_frequency;
  ExpressionText max_step;       // empty text: 2π/ω/16
};

// Reads and checks the shape of the section (names, keys, counts): an unknown
// key, a missing reset or direction, a dimension mismatch between the states
// and the equations are ModelFileError at their place in `file`.
ModelDefinition read_model_definition(const toml::table& model, const std::string& file);

// The [model] section of the scene file at `path` (malformed TOML is a
// ModelFileError at its line and column too).
ModelDefinition read_model_file(const std::string& path);

// Whether the scene text has a [model] section.
bool has_model_section(const toml::table& scene);

}  // namespace impactlab
