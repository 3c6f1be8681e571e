// A continuation from a scene: the type-erased request and result of
// continuation_of_scene (api/system_jobs.hpp), what the front ends read and
// write. Branches and two-parameter curves of a period-n orbit, their
// bifurcations and grazing points; the method is in docs/analysis.md
// ("Continuation"), the pieces that compute them:
//
//   continuation_problem.hpp   the section map as the drivers see it
//   branch_continuation.hpp    one branch (continue_branch): its driver,
//   branch_corrector.hpp         its corrector and step control,
//   bifurcation_location.hpp     its test functions and their location,
//   grazing_system.hpp           its grazing extended system
//   curve_continuation.hpp     a two-parameter curve (continue_curve)
//   stroboscopic_map_problem.hpp, impact_map_problem.hpp   the section maps of a system
//   run_continuation.hpp       the job for a concrete system (branches, doublings, curves)
//
// Types only: a translation unit that reads or writes a continuation includes
// this header alone.
#pragma once

#include <complex>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <impactlab/analysis/grazing_normal_form.hpp>

namespace impactlab {

// The state on the section: its N tangent components ((q, q̇), or a model
// file's N states).
using OrbitPoint = std::vector<double>;

// What a point found on a branch is.
enum class BifurcationType {
  fold,             // a multiplier through +1 where the branch turns back in p
  branch_point,     // a multiplier through +1 where it does not (pitchfork, transcritical)
  period_doubling,  // a multiplier through −1
  neimark_sacker,   // a complex pair through the unit circle
  grazing,          // a wall touched with zero normal velocity
  contact_onset,    // the contact phases per orbit grow
  contact_end,      // the contact phases per orbit shrink
  stick_onset,      // an impact starts to stick: its impulse reaches the friction cone's edge
  stick_end,        // an impact stops sticking and slides
  chatter_onset,    // a chatter into contact stops completing (chatter_onset.hpp)
  boundary,         // a ParameterBoundary crossed (its name: BifurcationPoint::boundary)
};

// Why a branch or a curve stopped.
enum class StopReason {
  end_of_range,         // p reached `to` (a curve: p₂ reached to2)
  left_range,           // the branch turned back past `from` (a curve: p₁ left its range)
  branch_point,         // the corrector fails below the smallest step
  signature_change,     // the impact signature changed (grazing)
  max_points,           // the point limit
  start_not_converged,  // no orbit found at the start
  neutral_drift,        // a held neutral component stopped returning: no periodic orbit
  no_tangent_map,       // the orbit crosses an event with a one-sided tangent map
                        // (an impulse on the friction cone's edge): no multipliers
};

// The bifurcation a two-parameter curve follows.
enum class CurveType {
  fold,             // det(M − I) = 0 (a branch point's curve too)
  period_doubling,  // det(M + I) = 0
  grazing,          // zero gap and zero gap rate at t_g
  contact_onset,    // the push on the mass at rest at its landing is zero (contact_landing.hpp)
  contact_end,      // the same condition, from a located contact_end point
  contact_boundary, // a scene's parameter boundary of that name is zero (the pendulum's
                    // V0·ω = g: ParameterBoundary, continuation_problem.hpp)
  neimark_sacker,   // det M − 1 = 0 (N = 2), ∏ᵢ<ⱼ(λᵢλⱼ − 1) = 0 (N > 2)
  chatter_onset,    // a chatter starts on the stable manifold of the self-similar
                    // chatter that accumulates where the push vanishes (chatter_onset.hpp)
};

// The names points.csv, continuation.json and Python use.
constexpr std::string_view to_string(BifurcationType type) {
  switch (type) {
    case BifurcationType::fold: return "fold";
    case BifurcationType::branch_point: return "branch_point";
    case BifurcationType::period_doubling: return "period_doubling";
    case BifurcationType::neimark_sacker: return "neimark_sacker";
    case BifurcationType::grazing: return "grazing";
    case BifurcationType::contact_onset: return "contact_onset";
    case BifurcationType::contact_end: return "contact_end";
    case BifurcationType::stick_onset: return "stick_onset";
    case BifurcationType::stick_end: return "stick_end";
    case BifurcationType::chatter_onset: return "chatter_onset";
    case BifurcationType::boundary: return "boundary";
  }
  return "unknown";
}

constexpr std::string_view to_string(StopReason reason) {
  switch (reason) {
    case StopReason::end_of_range: return "end_of_range";
    case StopReason::left_range: return "left_range";
    case StopReason::branch_point: return "branch_point";
    case StopReason::signature_change: return "signature_change";
    case StopReason::max_points: return "max_points";
    case StopReason::start_not_converged: return "start_not_converged";
    case StopReason::neutral_drift: return "neutral_drift";
    case StopReason::no_tangent_map: return "no_tangent_map";
  }
  return "unknown";
}

constexpr std::string_view to_string(CurveType type) {
  switch (type) {
    case CurveType::fold: return "fold";
    case CurveType::period_doubling: return "period_doubling";
    case CurveType::grazing: return "grazing";
    case CurveType::contact_onset: return "contact_onset";
    case CurveType::contact_end: return "contact_end";
    case CurveType::contact_boundary: return "contact_boundary";
    case CurveType::neimark_sacker: return "neimark_sacker";
    case CurveType::chatter_onset: return "chatter_onset";
  }
  return "unknown";
}

// The curve type named `text` (the option `curve`); none for another word.
constexpr std::optional<CurveType> parse_curve_type(std::string_view text) {
  for (const CurveType type : {CurveType::fold, CurveType::period_doubling, CurveType::grazing,
                               CurveType::contact_onset, CurveType::contact_end,
                               CurveType::contact_boundary, CurveType::neimark_sacker,
                               CurveType::chatter_onset})
    if (to_string(type) == text) return type;
  return std::nullopt;
}

// The curve that follows a located point of this type (a branch point's: the
// fold's); none for a type no curve follows.
constexpr std::optional<CurveType> curve_type_of(BifurcationType type) {
  switch (type) {
    case BifurcationType::fold:
    case BifurcationType::branch_point: return CurveType::fold;
    case BifurcationType::period_doubling: return CurveType::period_doubling;
    case BifurcationType::grazing: return CurveType::grazing;
    case BifurcationType::contact_onset: return CurveType::contact_onset;
    case BifurcationType::contact_end: return CurveType::contact_end;
    case BifurcationType::neimark_sacker: return CurveType::neimark_sacker;
    case BifurcationType::chatter_onset: return CurveType::chatter_onset;
    default: return std::nullopt;
  }
}

struct ContinuationRequest {
  double from = 0.0, to = 1.0;       // the parameter's range, run from `from` towards `to`
  OrbitPoint start{};              // a point of the orbit at p = from (a guess; corrected)
  double initial_step = 0.0;         // arclength (0: 1/100 of the range)
  double min_step = 0.0;             // (0: 1e-7 of the range)
  double max_step = 0.0;             // (0: 1/50 of the range)
  int max_points = 5000;
  int max_newton_iterations = 12;
  double tolerance = 1e-10;          // |F| ≤ tolerance (1 + |x|): continue's default (api/job_options)
  double parameter_difference = 0.0; // h of ∂F/∂p ≈ (P(p+h) − P(p−h)) / 2h (0: 1e-6 (1 + |p|))
  bool locate = true;                // locate the bifurcations detected
  bool normal_forms = true;          // a located grazing point's discontinuity map and normal form
};

struct BranchPoint {
  double parameter = 0.0;
  OrbitPoint state{};
  int impacts = 0;
  int contact_phases = 0;
  std::vector<std::complex<double>> multipliers;  // all N, largest modulus first
  bool stable = false;  // every multiplier strictly inside the unit circle
  double min_impact_speed = 0.0;
  double min_flight_gap = 0.0;
  int newton_iterations = 0;
  double step = 0.0;     // arclength step that reached it
  double phase = 0.0;    // rad: the section of `state`
};

// A located bifurcation point.
struct BifurcationPoint {
  BifurcationType type = BifurcationType::fold;
  std::string boundary;    // type boundary: the boundary's name (ParameterBoundary::name)
  double parameter = 0.0;
  OrbitPoint state{};
  std::vector<std::complex<double>> multipliers;
  double error_estimate = 0.0;  // bound on the parameter's error (the final bracket, or Newton's last step)
  double graze_time = std::numeric_limits<double>::quiet_NaN();  // s since the section (grazing)
  int graze_witness = -1;
  bool located = false;    // false: detected between two points only
  std::string note;
  // grazing (request.normal_forms): the discontinuity map and the local
  // normal form at the touch, its scenario and scalings (grazing_normal_form.hpp)
  std::optional<GrazingNormalForm> normal_form;
};

// The point's type as points.csv and Python name it: a boundary by its own name.
inline std::string_view type_name(const BifurcationPoint& point) {
  return point.type == BifurcationType::boundary ? std::string_view(point.boundary)
                                                 : to_string(point.type);
}

// The curve that follows this located point: its type's, and a boundary's
// the curve type of the same name; none for a point no curve follows.
inline std::optional<CurveType> curve_type_of(const BifurcationPoint& point) {
  return point.type == BifurcationType::boundary ? parse_curve_type(point.boundary)
                                                 : curve_type_of(point.type);
}

struct ContinuationResult {
  std::vector<BranchPoint> branch;
  std::vector<BifurcationPoint> points;
  StopReason stop_reason = StopReason::end_of_range;
  std::string stop_detail;
  int map_evaluations = 0;
};

// A point of a two-parameter curve of a fold, period doubling, grazing or
// contact onset/end point (analysis/curve_continuation.hpp).
struct CurvePoint {
  double p1 = 0.0, p2 = 0.0;
  OrbitPoint state{};                                  // on the requested section
  std::vector<std::complex<double>> multipliers;       // largest modulus first
  double graze_time = std::numeric_limits<double>::quiet_NaN();  // s since the requested section
  int impacts = 0;
  int newton_iterations = 0;
  double step = 0.0;                                   // the arclength that reached it
};

// A codimension-two point on a two-parameter curve: where a second
// condition holds on the curve as well as the curve's own.
enum class CodimensionTwoType {
  grazing_period_doubling,  // on a grazing curve: the virtual orbit's multiplier through −1
  grazing_fold,             // on a grazing curve: the virtual orbit's multiplier through +1
  grazing_scenario_change,  // on a grazing curve: its dominant multiplier through a threshold
                            // of the eigenvalue rule (1/4 or 2/3), or the sign of an
                            // impact's kick (K or an e_k) through zero, where the
                            // predicted scenario past the graze changes
  cusp,                     // on a fold curve: the curve's tangent has no parameter component
                            // (the fold's quadratic coefficient is zero; two fold curves meet)
  resonance_1_1,            // on a Neimark–Sacker curve: the pair on the unit circle meets at +1
  resonance_1_2,            // on a Neimark–Sacker curve: the pair meets at −1
  degenerate_period_doubling,  // on a period-doubling curve: the flip's cubic coefficient is
                               // zero (the doubled orbit's criticality changes)
};

constexpr std::string_view to_string(CodimensionTwoType type) {
  switch (type) {
    case CodimensionTwoType::grazing_period_doubling: return "grazing_period_doubling";
    case CodimensionTwoType::grazing_fold: return "grazing_fold";
    case CodimensionTwoType::grazing_scenario_change: return "grazing_scenario_change";
    case CodimensionTwoType::cusp: return "cusp";
    case CodimensionTwoType::resonance_1_1: return "resonance_1_1";
    case CodimensionTwoType::resonance_1_2: return "resonance_1_2";
    case CodimensionTwoType::degenerate_period_doubling: return "degenerate_period_doubling";
  }
  return "unknown";
}

// The other curve through a codimension-two point (`switch`) located on a
// curve of type `on`: at a grazing–period-doubling (grazing–fold) point the
// period doubling's (fold's) from a grazing curve, the grazing curve from
// the other; none through a change of the grazing scenario, a cusp (the
// fold curve through it is the curve itself), a resonance or a degenerate
// period doubling.
constexpr std::optional<CurveType> curve_through(CodimensionTwoType type, CurveType on) {
  switch (type) {
    case CodimensionTwoType::grazing_period_doubling:
      return on == CurveType::grazing ? CurveType::period_doubling : CurveType::grazing;
    case CodimensionTwoType::grazing_fold:
      return on == CurveType::grazing ? CurveType::fold : CurveType::grazing;
    case CodimensionTwoType::grazing_scenario_change: return std::nullopt;
    case CodimensionTwoType::cusp:
    case CodimensionTwoType::resonance_1_1:
    case CodimensionTwoType::resonance_1_2:
    case CodimensionTwoType::degenerate_period_doubling: return std::nullopt;
  }
  return std::nullopt;
}

struct CodimensionTwoPoint {
  CodimensionTwoType type = CodimensionTwoType::grazing_period_doubling;
  double p1 = 0.0, p2 = 0.0;
  OrbitPoint state{};                                  // on the requested section
  std::vector<std::complex<double>> multipliers;       // largest modulus first
  double graze_time = std::numeric_limits<double>::quiet_NaN();  // s since the requested section
  int graze_witness = -1;                              // the grazed wall's witness
  // bound on the error of p₁ and of p₂ (the larger, in each one's unit): the
  // final arclength bracket times the tangent's component
  double error_estimate = 0.0;
  bool located = false;  // false: detected between two curve points only
  std::string note;
};

struct CurveResult {
  CurveType type = CurveType::fold;
  std::vector<CurvePoint> curve;
  std::vector<CodimensionTwoPoint> points;  // codimension-two points, in the curve's order
  StopReason stop_reason = StopReason::end_of_range;
  std::string stop_detail;
  int map_evaluations = 0;
};

// A continuation from a scene (continuation_of_scene, api/system_jobs.hpp): the scene key
// continued, the orbit, where the branch starts, and the cascade to follow.
struct ContinuationJob {
  std::string parameter;           // scene key (omega, A, V0, ...)
  double from = 0.0, to = 1.0;     // its range, run from `from` towards `to`
  int period = 1;                  // n: the orbit's period in forcing periods
  double phase = 0.0;              // rad: the stroboscopic section ωt ≡ phase (mod 2π)
  // nonzero: the impact section of this wall (+1 / −1) instead, its state
  // (φ, q̇⁻): the forcing phase ωt of an impact with it in [0, 2π), and the
  // rate just before that impact
  int impact_wall = 0;
  double transient_periods = 100;  // periods run from the scene's initial state for the start
  bool has_start = false;          // start from `start` (N numbers on the section) instead of the transient's end
  OrbitPoint start{};
  int doublings = 0;               // period doublings to switch at (the cascade followed)
  ContinuationRequest numerics;    // from, to and start are set from the fields above
  // a two-parameter curve: with `second_parameter` set, the branch runs at
  // second_parameter = second_from, and the curve of the first located point
  // of `curve_type` (none: the first that a curve follows) is followed in
  // (parameter, second_parameter) from second_from towards second_to, within
  // [from, to] in the first
  std::string second_parameter;
  double second_from = 0.0, second_to = 1.0;
  std::optional<CurveType> curve_type;
};

// A component of the section state held fixed (analysis/neutral_component.hpp).
struct HeldComponent {
  std::size_t index = 0;  // in the full state
  double value = 0.0;     // its value, the start's
};

struct ContinuedBranch {
  int period = 1;  // forcing periods of the orbit on this branch
  ContinuationResult result;
};

// A two-parameter curve from one of the branches (job.second_parameter).
struct BranchCurve {
  int branch = 0;        // the branch it starts from (its index in branches)
  int period = 1;        // that branch's period (forcing periods)
  bool has_curve = false;  // the branch has a located point of the type to start from
  CurveResult curve;
  std::string note;      // why there is no curve
  // a curve through a codimension-two point (switch): that point's type;
  // none for a curve started from a point located on the branch
  std::optional<CodimensionTwoType> started_at;
};

// Where a curve starts, as curve.csv and Python name it: "branch", or the
// type of the codimension-two point it runs through.
constexpr std::string_view start_name(const BranchCurve& curve) {
  return curve.started_at ? to_string(*curve.started_at) : std::string_view("branch");
}

struct ContinuationJobResult {
  bool available = false;  // false: the oscillator/model has no Jacobians (see note)
  std::string note;
  std::size_t dimension = 2;  // N: the components of the states, the multipliers per point
  std::vector<ContinuedBranch> branches;  // the first, then each doubled one
  bool has_curve = false;                 // a curve was asked for and a point to start it found
  CurveResult curve;                      // the two-parameter curve (job.second_parameter)
  std::string curve_note;                 // why there is no curve, where one was asked for
  // a curve with doublings (`switch`): the curve of the same type from each
  // doubled branch's first located point of it, doubled_curves[k] from
  // branches[k + 1] (the cascade's boundaries in the plane)
  std::vector<BranchCurve> doubled_curves;
  // with `switch`: the curve through each located codimension-two point of
  // the first curve (a grazing–period-doubling point: the period-doubling
  // curve through it)
  std::vector<BranchCurve> switched_curves;
  // a component of the state along which the map was neutral, held at its
  // start value (analysis/neutral_component.hpp); every state and multiplier
  // list above has it back
  std::optional<HeldComponent> neutral;
};

}  // namespace impactlab
