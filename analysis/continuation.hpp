// Pseudo-arclength continuation of a period-n orbit, seen as a fixed point of
// the n-fold stroboscopic map Pⁿ(x; p) (or of the impact map of one wall,
// state (impact phase, q̇⁻)), with its bifurcations located on the
// branch: fold (a multiplier through +1), period doubling (through −1),
// Neimark–Sacker (a complex pair through the unit circle) and grazing (a wall
// touched with zero normal velocity: an interior flight extremum reaching a
// wall, or an impact velocity going to zero).
//
// The driver (continue_branch) knows no oscillator: it works on a
// ContinuationProblem, the section map and its probes as functions of the
// state on the section (its N tangent components: (q, q̇), or a model file's N
// states) and of one parameter p. The scene bindings
// build one for a concrete system (analysis/run_continuation.hpp).
//
// Method (docs/analysis.md, "Continuation"):
//  * unknowns y = (x, p), x the N components of the state on the section
//    ((q, q̇) below); equations F(x, p) = Pⁿ(x; p) − x = 0 and the
//    arclength condition τ·(y − y_pred) = 0; ∂F/∂x = M − I from the
//    saltation-corrected monodromy M, ∂F/∂p by a central difference of Pⁿ in p;
//  * Newton corrector; the step grows after easy corrections and is halved
//    where Newton fails, where the tangent turns by more than 30°, or where
//    the impact signature (the walls hit, in order) changes; the branch stops
//    below the smallest step; a contact phase appearing or ending alone does
//    not stop it;
//  * bifurcations are detected by sign changes of test functions between two
//    points (det(M − I), det(M + I), det M − 1 (for N > 2: ∏ᵢ<ⱼ (λᵢλⱼ − 1)),
//    the smallest flight gap, the
//    smallest impact speed) and located by a root finder (TOMS 748) on the
//    arclength between them, each trial point corrected onto the branch;
//  * a grazing point is then solved as an extended system in (q, q̇, p, t_g):
//    F = 0 with the wall's contacts near t_g suppressed (the virtual orbit
//    that passes through the graze), gap(t_g) = 0, gap rate(t_g) = 0; on the
//    impact section, a grazing of the section's own impact (where that map
//    ends) by the same system on the stroboscopic map of the same system
//    (ContinuationProblem::strobe), the point carried back onto the section;
//  * a change of the number of contact phases between two points is located
//    by bisection on the arclength between them (each trial point corrected
//    onto the branch) down to a bracket of 1e-10 of the range in p.
#pragma once

#include <cstddef>
#include <complex>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace impactlab {

// The state on the section: its N tangent components ((q, q̇), or a model
// file's N states).
using OrbitPoint = std::vector<double>;
// ∂Pⁿ/∂x, N × N, row-major: m[row][column].
using MonodromyMatrix = std::vector<std::vector<double>>;

// The Floquet multipliers (eigenvalues of M), largest modulus first (of a
// complex pair, the one with the positive imaginary part first).
std::vector<std::complex<double>> multipliers_of(const MonodromyMatrix& m);
// The test functions of a fold, det(M − I) = ∏ (λᵢ − 1), and of a period
// doubling, det(M + I) = ∏ (λᵢ + 1).
double det_minus_identity(const MonodromyMatrix& m);
double det_plus_identity(const MonodromyMatrix& m);

// Contacts of one wall suppressed in a time window: the virtual orbit through
// a grazing point. Times are measured from the section (s).
struct ContactWindow {
  int witness = -1;  // -1: none suppressed
  double from = 0.0, to = 0.0;
};

// One evaluation of the n-fold section map.
struct OrbitEvaluation {
  bool completed = false;      // the run reached the section again
  OrbitPoint image{};        // Pⁿ(x; p)
  MonodromyMatrix monodromy;   // ∂Pⁿ/∂x, saltation matrices included
  int impacts = 0;             // impacts over the n periods
  int contact_phases = 0;      // contact phases (sticking) over the n periods
  std::string signature;       // the walls of the events in order ("+1 +1 -1", "+1 c+1": contact)
  double min_impact_speed = std::numeric_limits<double>::infinity();  // min |q̇⁻| of the impacts
  // the smallest local minimum of a wall gap in flight (not at an impact), from
  // samples of the orbit; its time since the section (s) and its witness
  double min_flight_gap = std::numeric_limits<double>::infinity();
  double min_flight_gap_time = std::numeric_limits<double>::quiet_NaN();
  int min_flight_gap_witness = -1;
  // the time since the section (s) and witness of the impact of smallest speed
  double slowest_impact_time = std::numeric_limits<double>::quiet_NaN();
  int slowest_impact_witness = -1;
  std::vector<double> event_times;  // every event, time since the section (s)
  double span = 0.0;                // nT (s)
  double omega = 0.0;               // forcing frequency (rad/s)
};

// A witness (wall gap) and its rate along the orbit at a time since the section.
struct GapSample {
  bool completed = false;
  double value = 0.0;  // gap (the witness's unit: length or rad)
  double rate = 0.0;   // its time derivative along the flow
  OrbitPoint state{};  // the N components of the state there
};

// A boundary that depends on the parameter alone, reported where the branch
// crosses it (a sign change of `value`) and located exactly (the root of
// `value`, then the orbit corrected there): the pendulum's V0·ω = g, below
// which no contact phase can exist.
struct ParameterBoundary {
  std::string type;  // its type in points.csv
  std::string note;
  std::function<double(double p)> value;
};

// The section is ωt ≡ phase (mod 2π); the driver may move it off an impact
// that comes too close to it (where the stroboscopic map jumps) and reports
// every state on the requested `phase`.
struct ContinuationProblem {
  // Pⁿ(x; p) and what the orbit does on the way; `detailed` also samples the
  // flight gaps (a few times dearer)
  std::function<OrbitEvaluation(const OrbitPoint& x, double p, double phase, bool detailed,
                                const ContactWindow& suppressed)>
      evaluate;
  // the gap of `suppressed.witness` at time t since the section along the
  // orbit from x at p, with that wall's contacts in the window suppressed
  std::function<GapSample(const OrbitPoint& x, double p, double phase,
                          const ContactWindow& suppressed, double t)>
      gap_at;
  // the state reached from x on section `from` at the next section `to`
  std::function<std::optional<OrbitPoint>(const OrbitPoint& x, double p, double from, double to)>
      transport;
  double phase = 0.0;                // rad: the requested section
  // the driver may move a stroboscopic section off events (`transport`); an
  // impact section lies on its events and stays
  bool section_moves = true;
  double forcing_period_at_p = 0.0;  // nT at the start (s): the scale of the grazing window
  std::size_t dimension = 2;         // N: the components of an OrbitPoint
  std::vector<ParameterBoundary> boundaries;  // reported where the branch crosses them
  // The impact section only. Where the impact with the section's own wall
  // grazes (its speed goes to zero), the section is tangent to the flow and
  // the impact map ends, so that grazing is solved on the stroboscopic map of
  // the same system instead, by the same extended system as every grazing
  // (the wall's contacts suppressed near t_g): `strobe` is that map (its
  // phase set per call), `to_strobe(x, p, phase)` the state that the orbit
  // from the impact x on this section reaches at the next ωt ≡ phase (along
  // the virtual orbit: the section wall's contacts suppressed within nT/10 of
  // the impact), and `section_witness` the section wall's witness (−1: a
  // stroboscopic section, none of this).
  int section_witness = -1;
  std::shared_ptr<const ContinuationProblem> strobe;
  std::function<std::optional<OrbitPoint>(const OrbitPoint& x, double p, double phase)> to_strobe;
};

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
  std::string type;        // fold, period_doubling, neimark_sacker, grazing, impact_grazing, contact_onset, contact_end
  double parameter = 0.0;
  OrbitPoint state{};
  std::vector<std::complex<double>> multipliers;
  double error_estimate = 0.0;  // bound on the parameter's error (the final bracket, or Newton's last step)
  double graze_time = std::numeric_limits<double>::quiet_NaN();  // s since the section (grazing)
  int graze_witness = -1;
  bool located = false;    // false: detected between two points only
  std::string note;
};

struct ContinuationResult {
  std::vector<BranchPoint> branch;
  std::vector<BifurcationPoint> points;
  // end_of_range, branch_point (step below the smallest: a point the corrector
  // cannot pass), signature_change (the impact signature changed: grazing),
  // max_points, start_not_converged, run_stopped
  std::string stop_reason = "end_of_range";
  std::string stop_detail;
  int map_evaluations = 0;
};

// A point of a two-parameter curve of a fold, period doubling or grazing
// point (analysis/curve_continuation.hpp).
struct CurvePoint {
  double p1 = 0.0, p2 = 0.0;
  OrbitPoint state{};                                  // on the requested section
  std::vector<std::complex<double>> multipliers;       // largest modulus first
  double graze_time = std::numeric_limits<double>::quiet_NaN();  // s since the requested section
  int impacts = 0;
  int newton_iterations = 0;
  double step = 0.0;                                   // the arclength that reached it
};

struct CurveResult {
  std::string type;
  std::vector<CurvePoint> curve;
  // end_of_range (p₂ reached to2), left_range (p₁ left its range),
  // branch_point (the corrector fails below the smallest step), max_points,
  // start_not_converged
  std::string stop_reason = "end_of_range";
  std::string stop_detail;
  int map_evaluations = 0;
};

// Corrects `request.start` onto the orbit at p = from (Newton at fixed p) and
// continues the branch towards `to`.
ContinuationResult continue_branch(const ContinuationProblem& problem,
                                   const ContinuationRequest& request);

// Starts a branch from a point (x, p) along a given direction (dx, dp) of
// unit size instead of the branch's own tangent: the branch switch at a
// period doubling (the doubled orbit leaves along the −1 eigenvector, dp = 0).
// direction: N + 1 components.
ContinuationResult continue_branch_from(const ContinuationProblem& problem,
                                        const ContinuationRequest& request,
                                        const OrbitPoint& x, double p,
                                        const std::vector<double>& direction);

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
  // of `curve_type` (fold, period_doubling or grazing; empty: the first of
  // any) is followed in (parameter, second_parameter) from second_from
  // towards second_to, within [from, to] in the first
  std::string second_parameter;
  double second_from = 0.0, second_to = 1.0;
  std::string curve_type;
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
};

struct ContinuationJobResult {
  bool available = false;  // false: the oscillator/model has no Jacobians (see note)
  std::string note;
  std::size_t dimension = 2;  // N: the components of the states, the multipliers per point
  std::vector<ContinuedBranch> branches;  // the first, then each doubled one
  bool has_curve = false;                 // a curve was asked for and a point to start it found
  CurveResult curve;                      // the two-parameter curve (job.second_parameter)
  std::string curve_note;                 // why there is no curve, where one was asked for
  // a curve with doublings (--switch): the curve of the same type from each
  // doubled branch's first located point of it, doubled_curves[k] from
  // branches[k + 1] (the cascade's boundaries in the plane)
  std::vector<BranchCurve> doubled_curves;
};

// The eigenvector of M for the real multiplier nearest `multiplier`, unit length.
OrbitPoint eigenvector_for(const MonodromyMatrix& monodromy, double multiplier);

}  // namespace impactlab
