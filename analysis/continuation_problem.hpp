// The section map of a continuation as the drivers see it: a period-n orbit
// is a fixed point of the n-fold stroboscopic map Pⁿ(x; p) (or of the impact
// map of one wall, state (impact phase, q̇⁻)), given as functions of the
// state on the section (its N tangent components: (q, q̇), or a model file's
// N states) and of one parameter p. The drivers (branch_continuation.hpp,
// curve_continuation.hpp) know no oscillator; stroboscopic_map_problem.hpp
// and impact_map_problem.hpp build a problem for a concrete system.
#pragma once

#include <complex>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/floquet_multipliers.hpp>

namespace impactlab {

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
  int stick_impacts = 0;       // impacts whose contact point stops sliding (EventRecord::sticks)
  // an event's tangent map is one side's (an impulse on the friction cone's
  // edge, Transition::one_sided): the monodromy serves Newton, but the
  // orbit's multipliers do not exist
  bool one_sided = false;
  int one_sided_witness = -1;  // the flight witness of such an impact (its wall); −1: none
  int stuck_witness = -1;      // the flight witness of the last impact that stuck; −1: none
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
  // the landing of a contact phase whose push into the wall on the mass at
  // rest is nearest zero (contact_landing.hpp): that push (force per unit
  // mass; > 0: the contact phase holds) and its time since the section (s);
  // NaN where the orbit lands nowhere or the system has no stuck mode
  double landing_push = std::numeric_limits<double>::quiet_NaN();
  double landing_time = std::numeric_limits<double>::quiet_NaN();
  // the chatter whose margin to the onset of complete chatter is nearest
  // zero (chatter_onset.hpp): that margin (> 0 complete, < 0 it escapes;
  // NaN where no run resolves enough impacts), the difference between its
  // two neighbouring indices, the margin at each index k that the run
  // resolves, the real index K the margin is taken at, and the side of that
  // chatter (+1 it accumulates, −1 it does not, 0 no chatter)
  double chatter_margin = std::numeric_limits<double>::quiet_NaN();
  double chatter_spread = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> chatter_margins;
  double chatter_index = std::numeric_limits<double>::quiet_NaN();
  int chatter_side = 0;
  double span = 0.0;                // nT (s)
  double omega = 0.0;               // forcing frequency (rad/s)
};

// The orbit's Floquet multipliers, NaN where its map crosses an event with a
// one-sided tangent map (OrbitEvaluation::one_sided).
inline std::vector<std::complex<double>> multipliers_of(const OrbitEvaluation& orbit) {
  return orbit.one_sided ? missing_multipliers(orbit.monodromy.size())
                         : multipliers_of(orbit.monodromy);
}

// A witness (wall gap) and its rate along the orbit at a time since the section.
struct GapSample {
  bool completed = false;
  double value = 0.0;  // gap (the witness's unit: length or rad)
  double rate = 0.0;   // its time derivative along the flow
  OrbitPoint state{};  // the N components of the state there
};

// A boundary that depends on the parameter alone, reported where the branch
// crosses it (a sign change of `value`) with an orbit that has impacts on
// one side at least, and located exactly (the root of `value`, then the
// orbit corrected there): the pendulum's V0·ω = g, below which no contact
// phase can exist.
struct ParameterBoundary {
  std::string name;  // its type in points.csv
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
  // the local data at a grazing point (analysis/discontinuity_map.hpp): the
  // orbit from x at p on section `phase`, `suppressed` the touched wall's
  // window, touched at t since the section; empty on a problem without it
  std::function<GrazingLocalFlow(const OrbitPoint& x, double p, double phase,
                                 const ContactWindow& suppressed, double t)>
      grazing_flow;
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
  // The same map with every impact at the wall of flight witness k forced
  // to stick, whatever friction it needs: where an orbit holds an impulse on
  // the friction cone's edge over a range of parameters, it is a fixed point
  // of this map, which is smooth there, while the real map has no tangent
  // map (the rigid model with free spin, docs/rigidbody.md). Empty for a
  // system without a friction cone; null for a witness that is not a wall's.
  std::function<std::shared_ptr<const ContinuationProblem>(int witness)> stick_forced_at;
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

}  // namespace impactlab
