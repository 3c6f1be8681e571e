// A model section turned into functions: symbolic differentiation (GiNaC) of
// every vector field, witness and reset, C code for all of them compiled by
// the system compiler into a shared object, kept in the compile cache
// (compile_cache.hpp: where it is, what is checked before a load), and loaded
// with dlopen. When no compiler is usable the same expressions run on an
// interpreted evaluator, and the model says so (slow_path_reason).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/oscillators/model_file/compile_cache.hpp>
#include <impactlab/oscillators/model_file/model_definition.hpp>
#include <impactlab/oscillators/model_file/model_kernels.hpp>
#include <impactlab/oscillators/model_file/series_program.hpp>

namespace impactlab {

struct CompiledWall {
  std::string name;
  int side = 1;
  TriggerDirection direction = TriggerDirection::falling;
  bool has_sticking = false;
};

// The model's functions. Modes: 0 is free flight; 1 + k is resting on wall k
// (walls with a sticking mode only). N is the number of states.
class CompiledModel {
 public:
  CompiledModel() = default;
  CompiledModel(const CompiledModel&) = delete;
  CompiledModel& operator=(const CompiledModel&) = delete;
  ~CompiledModel();

  // --- what the model is ---
  std::string file;
  std::vector<std::string> states;
  std::vector<ModelParameter> parameters;
  std::vector<CompiledWall> walls;
  std::vector<std::string> mode_names;  // "free", then "stuck_<wall name>"

  // --- its functions ---
  Kernel free_rhs;        // f(x, t) in free flight (N)
  Kernel free_jacobian;   // ∂f/∂x (N × N, row-major)
  Kernel scalars;         // ω, max_step (parameters only)
  std::vector<Kernel> gap;             // per wall: h, ḣ along the free flow
  std::vector<Kernel> gap_gradient;    // per wall: ∂h/∂x (N)
  std::vector<Kernel> reset;           // per wall: x⁺ (N), then the restitution r (−1 for a map)
  std::vector<Kernel> reset_jacobian;  // per wall: ∂x⁺/∂x (N × N), then ∂x⁺/∂t (N)
  std::vector<Kernel> stick_rhs;       // per wall: the vector field at rest on it (N)
  std::vector<Kernel> stick_jacobian;  // per wall: its ∂/∂x (N × N)
  std::vector<Kernel> stick_state;     // per wall: the state on the wall (N)
  std::vector<Kernel> stick_force;     // per wall: F, Ḟ, F̈ along the sticking flow
  std::vector<Kernel> stick_force_gradient;  // per wall: ∂F/∂x (N)
  // per wall: the damping c = −∂ḧ/∂ḣ (1/time) and stiffness κ = ∂ḧ/∂h
  // (1/time²) of the gap's acceleration along the free flow, for the
  // accumulation estimate (contact/accumulation.hpp), then the size of the
  // gap's terms (the sticking table's gap_scale; 0 where not given)
  std::vector<Kernel> chatter;
  // --- the same over a number type, for the Taylor stepper (series_program.hpp):
  // the right-hand sides (N) and the witnesses with their rates (h, ḣ; F, Ḟ).
  // All empty where a kernel has an operation without a series:
  // series_refusal then says which ---
  SeriesProgram free_rhs_series;
  std::vector<SeriesProgram> gap_series;          // per wall
  std::vector<SeriesProgram> stick_rhs_series;    // per wall (empty without sticking)
  std::vector<SeriesProgram> stick_force_series;  // per wall (empty without sticking)
  std::string series_refusal;  // e.g. "the free right-hand side uses exp"; empty: all there
  // every free-flight expression as written (right-hand sides, witnesses,
  // restitutions, ω, max_step), for the check at the initial state
  Kernel written;
  std::vector<ExpressionText> written_expressions;

  // --- how it was built ---
  std::string c_source;           // the generated C (model_c_source.hpp), compiled or not
  bool compiled = false;          // false: the interpreted slow path
  std::string slow_path_reason;   // why not compiled (empty when compiled)
  std::string library;            // the shared object's path (empty when not kept)
  bool from_cache = false;        // the shared object was already there
  std::string cache_note;         // why the cache was bypassed (empty when used)
  double build_seconds = 0.0;     // symbolic work + code generation + compilation (s)

  // storage behind the kernels
  void* library_handle = nullptr;
  int library_descriptor = -1;  // the loaded object's open file (compile_cache.hpp)
  std::vector<SlotProgram> programs;
};

// Differentiates, generates, compiles (or finds in the cache) and loads.
// ModelFileError for expressions that do not make sense (unknown symbols,
// cycles among definitions, a Newton reset whose witness rate does not depend
// on its velocity, ...). Never fails for a missing compiler: that is the slow path.
std::shared_ptr<const CompiledModel> compile_model(const ModelDefinition& definition,
                                                   const CompileOptions& options);

// ModelFileError at the first written expression that is not finite at (x0, t0)
// with parameters p.
void check_initial_values(const CompiledModel& model, const std::vector<double>& x0, double t0,
                          const std::vector<double>& p);

}  // namespace impactlab
