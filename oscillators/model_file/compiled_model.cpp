#include <impactlab/oscillators/model_file/compiled_model.hpp>

#include <dlfcn.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <ginac/ginac.h>

#include <impactlab/oscillators/model_file/kernel_code.hpp>
#include <impactlab/oscillators/model_file/model_c_source.hpp>
#include <impactlab/oscillators/model_file/model_expression.hpp>

namespace impactlab {

namespace {

using Expressions = std::vector<GiNaC::ex>;

// The most nodes an expression may have with its definitions written out,
// where a definition used n times is written n times. GiNaC differentiates
// that tree (its work grows with the tree, although the code generated from
// it computes each subexpression once): a chain of definitions that each name
// the one before three times grows threefold per link.
constexpr std::size_t max_written_nodes = 1000000;

// The number of nodes of `e` written out (saturating at max_written_nodes +
// 1), each shared subexpression counted once per use but computed once (the
// ex is held in `known`, so that no address is reused).
std::size_t written_nodes(const GiNaC::ex& e,
                          std::map<const GiNaC::basic*, std::pair<GiNaC::ex, std::size_t>>& known) {
  const GiNaC::basic* node = &GiNaC::ex_to<GiNaC::basic>(e);
  if (const auto found = known.find(node); found != known.end()) return found->second.second;
  std::size_t nodes = 1;
  for (std::size_t i = 0; i < e.nops(); ++i)
    nodes = std::min(nodes + written_nodes(e.op(i), known), max_written_nodes + 1);
  known.emplace(node, std::pair{e, nodes});
  return nodes;
}

// ---------------------------------------------------------------------------
// symbolic stage: every kernel's outputs as GiNaC expressions in x[i], t, p[j]

// The symbols and the parsed expressions of one model.
class SymbolicModel {
 public:
  explicit SymbolicModel(const ModelDefinition& model) : model_(model), time_("t") {
    for (std::size_t i = 0; i < model.states.size(); ++i)
      states_.emplace_back(fmt::format("x[{}]", i));
    for (std::size_t j = 0; j < model.parameters.size(); ++j)
      parameters_.emplace_back(fmt::format("p[{}]", j));
  }

  [[nodiscard]] std::size_t size() const { return states_.size(); }
  [[nodiscard]] const GiNaC::realsymbol& state(std::size_t i) const { return states_[i]; }
  [[nodiscard]] const GiNaC::realsymbol& time() const { return time_; }

  // `text` parsed, with its definitions written out: refused above
  // max_written_nodes nodes, since differentiation works on that tree
  GiNaC::ex parse(const ExpressionText& text) {
    GiNaC::ex value = parse_at(text, 0).value;
    std::map<const GiNaC::basic*, std::pair<GiNaC::ex, std::size_t>> known;
    if (written_nodes(value, known) > max_written_nodes)
      throw ModelFileError(text.position, text.key,
                           fmt::format("grows to more than {} terms once its definitions are "
                                       "written out",
                                       max_written_nodes));
    return value;
  }

  [[nodiscard]] std::size_t state_index(const std::string& name) const {
    for (std::size_t i = 0; i < model_.states.size(); ++i)
      if (model_.states[i] == name) return i;
    return size();
  }

  // whether e depends on the state or the time at all
  [[nodiscard]] bool varies(const GiNaC::ex& e) const {
    if (e.has(time_)) return true;
    for (const auto& x : states_)
      if (e.has(x)) return true;
    return false;
  }

  // d/dt of e along the vector field f (a list of N expressions)
  [[nodiscard]] GiNaC::ex rate(const GiNaC::ex& e, const Expressions& f) const {
    GiNaC::ex total = e.diff(time_);
    for (std::size_t i = 0; i < size(); ++i) total += e.diff(states_[i]) * f[i];
    return total;
  }
  [[nodiscard]] Expressions gradient(const GiNaC::ex& e) const {
    Expressions g;
    for (std::size_t i = 0; i < size(); ++i) g.push_back(e.diff(states_[i]));
    return g;
  }
  [[nodiscard]] Expressions jacobian(const Expressions& f) const {
    Expressions j;
    for (const auto& fi : f)
      for (std::size_t i = 0; i < size(); ++i) j.push_back(fi.diff(states_[i]));
    return j;
  }

 private:
  // `text` parsed at nesting level `depth` (that of the name that refers to it)
  ParsedExpression parse_at(const ExpressionText& text, std::size_t depth) {
    const NameResolver resolver = [this](std::string_view name, const SourcePosition& where,
                                         std::size_t at_depth) { return resolve(name, where, at_depth); };
    return parse_expression(text, resolver, depth);
  }

  std::optional<ParsedExpression> resolve(std::string_view name, const SourcePosition& where,
                                          std::size_t depth) {
    if (name == "t") return ParsedExpression{GiNaC::ex(time_)};
    for (std::size_t i = 0; i < model_.states.size(); ++i)
      if (model_.states[i] == name) return ParsedExpression{GiNaC::ex(states_[i])};
    for (std::size_t j = 0; j < model_.parameters.size(); ++j)
      if (model_.parameters[j].name == name) return ParsedExpression{GiNaC::ex(parameters_[j])};
    for (const auto& [definition, text] : model_.definitions) {
      if (definition != name) continue;
      if (const auto done = definitions_.find(definition); done != definitions_.end())
        return done->second;
      if (!in_progress_.insert(definition).second)
        throw ModelFileError(where, text.key,
                             "circular definition: '" + definition + "' depends on itself");
      const ParsedExpression parsed = parse_at(text, depth);
      in_progress_.erase(definition);
      definitions_.emplace(definition, parsed);
      return parsed;
    }
    return std::nullopt;
  }

  const ModelDefinition& model_;
  GiNaC::realsymbol time_;
  std::vector<GiNaC::realsymbol> states_;
  std::vector<GiNaC::realsymbol> parameters_;
  std::map<std::string, ParsedExpression> definitions_;
  std::set<std::string> in_progress_;
};

// Where each kernel sits in the list of kernels.
struct KernelLayout {
  std::size_t free_rhs = 0, free_jacobian = 0, scalars = 0, written = 0;
  std::vector<std::size_t> gap, gap_gradient, reset, reset_jacobian;
  std::vector<std::size_t> stick_rhs, stick_jacobian, stick_state, stick_force, stick_force_gradient;
  std::vector<std::size_t> chatter;
};

constexpr std::size_t no_kernel = static_cast<std::size_t>(-1);

// The Newton reset along a velocity: ḣ⁺ = −r ḣ⁻ solved for v (one Newton step,
// exact where ḣ is affine in v, as for any mechanical gap), and the position
// put back on the wall, q⁺ = q − h/∂h/∂q (exact where h is affine in q).
// A derivative is zero where GiNaC's evaluation makes it zero; nothing is
// expanded or normalised here or below (either can take unbounded time: the
// expansion of (x + v + t + k)^1000 has half a billion terms). A derivative
// that vanishes only after expansion leaves a reset that divides by zero,
// which the run stops at (non_finite_state) or refuses at the initial state.
Expressions newton_reset(SymbolicModel& symbols, const ModelWall& wall, const GiNaC::ex& gap,
                         const GiNaC::ex& gap_rate, const GiNaC::ex& restitution) {
  Expressions after;
  for (std::size_t i = 0; i < symbols.size(); ++i) after.emplace_back(symbols.state(i));
  const std::size_t v = symbols.state_index(wall.reset.velocity);
  const GiNaC::ex sensitivity = gap_rate.diff(symbols.state(v));
  if (sensitivity.is_zero())
    throw ModelFileError(wall.reset.where, wall.witness.key,
                         "the witness's rate does not depend on the velocity '" +
                             wall.reset.velocity + "': Newton's law cannot change it");
  after[v] = symbols.state(v) - (1 + restitution) * gap_rate / sensitivity;
  if (!wall.reset.position.empty()) {
    const std::size_t q = symbols.state_index(wall.reset.position);
    const GiNaC::ex slope = gap.diff(symbols.state(q));
    if (slope.is_zero())
      throw ModelFileError(wall.reset.where, wall.witness.key,
                           "the witness does not depend on the position '" + wall.reset.position + "'");
    after[q] = symbols.state(q) - gap / slope;
  }
  return after;
}

// The gap's acceleration ḧ along the free flow, linearised in the gap and its
// rate as the accumulation estimate's local model has it
// (contact/accumulation.hpp: z̈ = −a − c ż + κ z): c = −∂ḧ/∂ḣ and κ = ∂ḧ/∂h,
// each holding the other and every state that neither moves fixed. ḣ is moved
// by the reset's velocity v alone (h is a function of positions: it does not
// depend on v), so c = −(∂ḧ/∂v)/(∂ḣ/∂v); h is moved by a position q (the
// reset's `position`, else the first state h depends on other than v), with v
// moved along to hold ḣ, so κ = (∂ḧ/∂q − (∂ḧ/∂v) (∂ḣ/∂q)/(∂ḣ/∂v))/(∂h/∂q).
// For the linear impact oscillator's gap σ − x: c = 2ζ, κ = −1.
// Returns c, κ, then the wall's gap_scale (0 where not given).
Expressions chatter_coefficients(SymbolicModel& symbols, const ModelWall& wall,
                                 const GiNaC::ex& gap, const GiNaC::ex& gap_rate,
                                 const Expressions& f) {
  const GiNaC::ex scale =
      wall.sticking.gap_scale.text.empty() ? GiNaC::ex(0) : symbols.parse(wall.sticking.gap_scale);
  const GiNaC::ex gap_acceleration = symbols.rate(gap_rate, f);
  const std::size_t v = symbols.state_index(wall.reset.velocity);
  const GiNaC::ex rate_by_velocity = gap_rate.diff(symbols.state(v));  // nonzero (newton_reset)
  const GiNaC::ex acceleration_by_velocity = gap_acceleration.diff(symbols.state(v));
  const GiNaC::ex damping = -acceleration_by_velocity / rate_by_velocity;
  std::size_t q = wall.reset.position.empty() ? symbols.size() : symbols.state_index(wall.reset.position);
  for (std::size_t i = 0; i < symbols.size() && q == symbols.size(); ++i)
    if (i != v && !gap.diff(symbols.state(i)).is_zero()) q = i;
  if (q == symbols.size()) return {damping, 0, scale};  // h depends on no position
  const GiNaC::ex stiffness =
      (gap_acceleration.diff(symbols.state(q)) -
       acceleration_by_velocity * gap_rate.diff(symbols.state(q)) / rate_by_velocity) /
      gap.diff(symbols.state(q));
  return {damping, stiffness, scale};
}

// `e` for real arguments: every state, parameter and time is real, and so is
// every value a model computes, so conjugate(u) and real_part(u) are u and
// imag_part(u) is 0. GiNaC's derivative of abs, (u' conj(u) + u conj(u'))/(2|u|),
// keeps conj(u) where it cannot prove u real (asin, acos, log, atan2, powers),
// and abs of a power keeps real_part of the exponent: written for real u, the
// derivative is u' u/|u|, which C and the interpreted evaluator have.
// Expressions holding none of these are returned as they are (the same C
// source as before).
GiNaC::ex for_real_arguments(const GiNaC::ex& e) {
  const GiNaC::ex u = GiNaC::wild();
  const GiNaC::lst real_rules = {GiNaC::conjugate_function(u).hold() == u,
                                 GiNaC::real_part_function(u).hold() == u,
                                 GiNaC::imag_part_function(u).hold() == 0};
  GiNaC::ex result = e;
  for (const GiNaC::ex& rule : real_rules)
    if (result.has(rule.lhs())) result = result.subs(rule);
  return result;
}

// Whether every number in `e` is a finite real double (the C code and the
// interpreted evaluator hold numbers as doubles). Each shared subexpression
// is visited once.
bool numbers_are_finite_doubles(const GiNaC::ex& e) {
  std::vector<GiNaC::ex> pending{e};
  // held, so that no address is reused by another subexpression meanwhile
  std::map<const GiNaC::basic*, GiNaC::ex> seen;
  while (!pending.empty()) {
    const GiNaC::ex next = pending.back();
    pending.pop_back();
    if (!seen.emplace(&GiNaC::ex_to<GiNaC::basic>(next), next).second) continue;
    if (GiNaC::is_a<GiNaC::numeric>(next)) {
      const GiNaC::numeric& number = GiNaC::ex_to<GiNaC::numeric>(next);
      if (!number.is_real() || !std::isfinite(number.to_double())) return false;
      continue;
    }
    for (std::size_t i = 0; i < next.nops(); ++i) pending.push_back(next.op(i));
  }
  return true;
}

// The series programs of the right-hand sides and the witnesses
// (series_program.hpp), or none and the reason where one of them has an
// operation without a series.
void attach_series_programs(CompiledModel& model, const std::vector<KernelCode>& kernels,
                            const KernelLayout& layout) {
  const std::size_t n = model.states.size();
  struct Need {
    std::string what;
    std::size_t kernel;
    std::size_t outputs;
  };
  std::vector<Need> needs{{"the free right-hand side", layout.free_rhs, n}};
  for (std::size_t k = 0; k < model.walls.size(); ++k) {
    const std::string& wall = model.walls[k].name;
    needs.push_back({"the gap to wall " + wall, layout.gap[k], 2});
    needs.push_back({"the right-hand side at rest on wall " + wall, layout.stick_rhs[k], n});
    needs.push_back({"the push on wall " + wall, layout.stick_force[k], 2});
  }
  for (const Need& need : needs) {
    if (need.kernel == no_kernel) continue;
    if (const std::string why = series_refusal(kernels[need.kernel], need.outputs); !why.empty()) {
      model.series_refusal = fmt::format("{}: {}", need.what, why);
      return;
    }
  }
  auto program = [&](std::size_t kernel, std::size_t outputs) {
    return kernel == no_kernel ? SeriesProgram{} : SeriesProgram(kernels[kernel], outputs);
  };
  model.free_rhs_series = program(layout.free_rhs, n);
  for (std::size_t k = 0; k < model.walls.size(); ++k) {
    model.gap_series.push_back(program(layout.gap[k], 2));
    model.stick_rhs_series.push_back(program(layout.stick_rhs[k], n));
    model.stick_force_series.push_back(program(layout.stick_force[k], 2));
  }
}

// The most operations one kernel may take (kernel_code.hpp): each distinct
// subexpression is computed once however often it is used, so this bounds
// the C source and the compiler's work, while a chain of definitions that
// names the one before several times stays far below it.
constexpr std::size_t max_kernel_operations = 200000;

// All kernels of the model, in the order of `layout`.
std::vector<KernelCode> build_kernels(const ModelDefinition& model, KernelLayout& layout,
                                      std::vector<ExpressionText>& written_texts) {
  SymbolicModel symbols(model);
  std::vector<KernelCode> kernels;
  auto add = [&](Expressions outputs) {
    for (GiNaC::ex& output : outputs) {
      output = for_real_arguments(output);
      if (!numbers_are_finite_doubles(output))
        throw ModelFileError(model.rhs_where, "model",
                             "an expression or one of its derivatives holds a number beyond the "
                             "range of a double: C code cannot hold it");
    }
    try {
      kernels.push_back(kernel_code(outputs, max_kernel_operations));
    } catch (const std::length_error&) {
      throw ModelFileError(model.rhs_where, "model",
                           fmt::format("an expression or one of its derivatives takes more than "
                                       "{} operations to compute",
                                       max_kernel_operations));
    }
    return kernels.size() - 1;
  };
  Expressions written;
  auto note = [&](const ExpressionText& text, const GiNaC::ex& value) {
    written.push_back(value);
    written_texts.push_back(text);
    return value;
  };

  Expressions f;
  for (const auto& [state, text] : model.rhs) f.push_back(note(text, symbols.parse(text)));
  layout.free_rhs = add(f);
  layout.free_jacobian = add(symbols.jacobian(f));

  const GiNaC::ex omega = note(model.forcing_frequency, symbols.parse(model.forcing_frequency));
  const GiNaC::ex max_step = model.max_step.text.empty()
                                 ? 2 * GiNaC::Pi / omega / 16
                                 : note(model.max_step, symbols.parse(model.max_step));
  for (const auto& [e, text] : {std::pair{omega, &model.forcing_frequency}, std::pair{max_step, &model.max_step}}) {
    if (symbols.varies(e))
      throw ModelFileError(text->position, text->key, "may depend on parameters only");
  }
  layout.scalars = add({omega, max_step});

  for (const ModelWall& wall : model.walls) {
    const GiNaC::ex h = note(wall.witness, symbols.parse(wall.witness));
    const GiNaC::ex h_rate = symbols.rate(h, f);
    if (!symbols.varies(h))
      throw ModelFileError(wall.witness.position, wall.witness.key,
                           "the witness is constant: it never crosses zero");
    layout.gap.push_back(add({h, h_rate}));
    layout.gap_gradient.push_back(add(symbols.gradient(h)));

    Expressions after;
    GiNaC::ex restitution = -1;  // a map reset has none
    if (wall.reset.kind == ModelReset::Kind::newton) {
      restitution = note(wall.reset.restitution, symbols.parse(wall.reset.restitution));
      after = newton_reset(symbols, wall, h, h_rate, restitution);
    } else {
      for (std::size_t i = 0; i < symbols.size(); ++i) after.emplace_back(symbols.state(i));
      for (const auto& [state, text] : wall.reset.map)
        after[symbols.state_index(state)] = symbols.parse(text);
    }
    Expressions reset_jacobian = symbols.jacobian(after);
    for (const auto& component : after) reset_jacobian.push_back(component.diff(symbols.time()));
    after.push_back(restitution);
    layout.reset.push_back(add(after));
    layout.reset_jacobian.push_back(add(reset_jacobian));

    if (!wall.has_sticking) {
      for (auto* slot : {&layout.stick_rhs, &layout.stick_jacobian, &layout.stick_state,
                         &layout.stick_force, &layout.stick_force_gradient, &layout.chatter})
        slot->push_back(no_kernel);
      continue;
    }
    Expressions stuck_f, stuck_state;
    for (const auto& [state, text] : wall.sticking.rhs) stuck_f.push_back(symbols.parse(text));
    for (const auto& [state, text] : wall.sticking.state) stuck_state.push_back(symbols.parse(text));
    const GiNaC::ex force = symbols.parse(wall.sticking.force);
    const GiNaC::ex force_rate = symbols.rate(force, stuck_f);
    layout.stick_rhs.push_back(add(stuck_f));
    layout.stick_jacobian.push_back(add(symbols.jacobian(stuck_f)));
    layout.stick_state.push_back(add(stuck_state));
    layout.stick_force.push_back(add({force, force_rate, symbols.rate(force_rate, stuck_f)}));
    layout.stick_force_gradient.push_back(add(symbols.gradient(force)));
    layout.chatter.push_back(add(chatter_coefficients(symbols, wall, h, h_rate, f)));
  }
  layout.written = add(written);
  return kernels;
}

}  // namespace

CompiledModel::~CompiledModel() {
  if (library_handle) dlclose(library_handle);
  if (library_descriptor >= 0) ::close(library_descriptor);
}

std::shared_ptr<const CompiledModel> compile_model(const ModelDefinition& definition,
                                                   const CompileOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  auto model = std::make_shared<CompiledModel>();
  model->file = definition.file;
  model->states = definition.states;
  model->parameters = definition.parameters;
  model->mode_names.push_back("free");
  for (const ModelWall& wall : definition.walls) {
    model->walls.push_back({wall.name, wall.side, wall.direction, wall.has_sticking});
    model->mode_names.push_back("stuck_" + wall.name);
  }

  KernelLayout layout;
  const std::vector<KernelCode> kernels = [&] {
    try {
      return build_kernels(definition, layout, model->written_expressions);
    } catch (const BadInput&) {
      throw;
    } catch (const std::exception& error) {
      // GiNaC's own refusals while it differentiates, for example of 0^v,
      // whose derivative holds log(0): "power::eval(): division by zero"
      throw ModelFileError(definition.rhs_where, "model",
                           fmt::format("its derivatives cannot be formed ({}), as for a "
                                       "power of zero such as 0^v",
                                       error.what()));
    }
  }();

  // compiled, where a compiler and the cache are usable
  model->c_source = model_c_source(kernels);
  std::vector<Kernel> loaded(kernels.size());
  if (options.use_compiler) {
    const LoadedObject object = load_or_compile(model->c_source, options);
    std::string why = object.why;
    model->cache_note = object.cache_note;
    if (object.handle) {
      model->library_handle = object.handle;
      model->library_descriptor = object.descriptor;
      model->library = object.path;
      model->from_cache = object.from_cache;
      for (std::size_t k = 0; k < kernels.size() && why.empty(); ++k) {
        void* symbol = dlsym(object.handle, fmt::format("impactlab_kernel_{}", k).c_str());
        if (!symbol) why = fmt::format("{} lacks kernel {}", object.path, k);
        loaded[k].compiled = reinterpret_cast<KernelFunction>(symbol);
      }
    }
    model->compiled = why.empty();
    model->slow_path_reason = why;
  } else {
    model->slow_path_reason = "compilation switched off";
  }
  // the interpreted slow path
  if (!model->compiled) {
    model->programs.reserve(kernels.size());
    for (const KernelCode& code : kernels) model->programs.emplace_back(code);
    for (std::size_t k = 0; k < kernels.size(); ++k) loaded[k] = {nullptr, &model->programs[k]};
  }

  auto kernel = [&](std::size_t index) { return index == no_kernel ? Kernel{} : loaded[index]; };
  auto kernel_list = [&](const std::vector<std::size_t>& indices) {
    std::vector<Kernel> list;
    for (auto index : indices) list.push_back(kernel(index));
    return list;
  };
  model->free_rhs = kernel(layout.free_rhs);
  model->free_jacobian = kernel(layout.free_jacobian);
  model->scalars = kernel(layout.scalars);
  model->written = kernel(layout.written);
  model->gap = kernel_list(layout.gap);
  model->gap_gradient = kernel_list(layout.gap_gradient);
  model->reset = kernel_list(layout.reset);
  model->reset_jacobian = kernel_list(layout.reset_jacobian);
  model->stick_rhs = kernel_list(layout.stick_rhs);
  model->stick_jacobian = kernel_list(layout.stick_jacobian);
  model->stick_state = kernel_list(layout.stick_state);
  model->stick_force = kernel_list(layout.stick_force);
  model->stick_force_gradient = kernel_list(layout.stick_force_gradient);
  model->chatter = kernel_list(layout.chatter);
  attach_series_programs(*model, kernels, layout);
  model->build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return model;
}

void check_initial_values(const CompiledModel& model, const std::vector<double>& x0, double t0,
                          const std::vector<double>& p) {
  std::vector<double> values(model.written_expressions.size());
  model.written(x0.data(), t0, p.data(), values.data());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::isfinite(values[i])) continue;
    const ExpressionText& text = model.written_expressions[i];
    throw ModelFileError(text.position, text.key,
                         fmt::format("evaluates to {} at the initial state (t = {}) in {} = \"{}\"",
                                     values[i], t0, text.key, text.text));
  }
}

}  // namespace impactlab
