// Attractors found by sampling and followed across a parameter: at each value
// of the parameter, the samples (runs from initial states drawn from a box,
// analysis/initial_box.hpp) are told apart by the attractor they settle on
// (analysis/basins.hpp: period, impacts, contact and a canonical section
// point within a tolerance), and each attractor is described by features an
// impact oscillator has of its own:
//
//   period m (forcing periods of its cycle on the section) and impacts n per
//   cycle: the (m, n) label;
//   contact: whether a sticking or sliding phase is part of it, and how many
//   contact phases begin or end per forcing period;
//   the smallest impact speed |q̇| over its samples' records: how near the
//   orbit is to grazing (0 at a grazing impact);
//   its m section points, from the canonical point on, in time order;
//   the largest Lyapunov exponent, averaged over its samples, where asked;
//   its basin fraction f = k/K (k of the K samples settle on it) with the
//   binomial standard error sqrt(f (1 − f) / K).
//
// From one value to the next an attractor keeps its id when their section
// point sets lie within the match tolerance of each other: the distance of
// two sets A and B is the Hausdorff distance
//   d(A, B) = max( max_a min_b |a − b|, max_b min_a |a − b| )
// relative to 1 + the largest |(q, q̇)| of both, so that an orbit and its
// mirror image, or two period-1 orbits with different points, are different
// attractors, while a period doubling (one point becoming two nearby points)
// keeps its id. Pairs are matched greedily, the closest first, each at most
// once. What is left over is an event: an attractor of the new value matched
// to none is born (`appear`), or, where its nearest old attractor within the
// tolerance was taken by a closer one, split off from that one (`split`); an
// old attractor matched to none is gone (`vanish`), or, where its nearest new
// attractor within the tolerance was taken, merged into it (`merge`).
// Samples that settle on no periodic attractor (chaos, a torus, a period over
// max_period, a run stopped early) are attractor 0: they are counted, with
// their fraction, but not followed.
#pragma once

#include <array>
#include <string_view>
#include <vector>

#include <impactlab/analysis/basins.hpp>

namespace impactlab {

using SectionPointSet = std::vector<std::array<double, 2>>;  // (q, q̇) points

struct SampledAttractor {
  int id = 0;                         // followed id along the parameter (1, 2, ...)
  int period = 0;                     // m: forcing periods of its cycle on the section
  double impacts_per_period = 0.0;    // impacts per forcing period
  int impacts_per_cycle = 0;          // n: impacts in its m periods, rounded
  bool contact = false;               // a contact (sticking/sliding) phase in it
  double contact_phases_per_period = 0.0;  // contact phases begun or ended per forcing period
  double min_impact_speed = 0.0;      // smallest |q̇| before an impact (q per time unit); NaN: none
  double lyapunov = 0.0;              // mean largest exponent of its samples (1/time); NaN: none
  std::array<double, 2> point{};      // canonical section point (analysis/basins.hpp)
  SectionPointSet cycle;              // its m section points, from the canonical one on
  int samples = 0;                    // k: samples that settle on it
  double fraction = 0.0;              // k / K
  double fraction_error = 0.0;        // sqrt(f (1 − f) / K)
};

// The attractors of one parameter value.
struct AttractorsAtValue {
  int index = 0;       // the value's index along the parameter
  double value = 0.0;  // the parameter's value
  int samples = 0;     // K: samples run at this value
  std::vector<SampledAttractor> attractors;  // by first appearance in sample order
  int unclassified = 0;                      // samples on no periodic attractor (attractor 0)
  // per sample, in sample order: 1 + the position of its attractor in
  // `attractors`, or 0 (none found)
  std::vector<int> sample_attractor;
};

// The attractors of the samples of one value, given in sample order, told
// apart at `tolerance` (relative distance of canonical points). Their ids
// are 0 until follow_attractors numbers them.
AttractorsAtValue attractors_at_value(int index, double value,
                                      const std::vector<const SweepRecord*>& records,
                                      double tolerance);

// The binomial standard error of a fraction f of `samples` samples.
double fraction_error(double fraction, int samples);

// d(A, B) above: the relative Hausdorff distance of two point sets
// (+∞ where either is empty).
double point_set_distance(const SectionPointSet& a, const SectionPointSet& b);

enum class AttractorChange { appear, vanish, merge, split };
std::string_view to_string(AttractorChange change);

// Where the set of attractors changes: between the values at index − 1 and
// index.
struct AttractorEvent {
  AttractorChange change = AttractorChange::appear;
  int index = 0;       // the first value index where the change shows
  int attractor = 0;   // the id that appears, vanishes, merges or splits off
  int other = 0;       // merge: the id it merged into; split: the id it split from; else 0
};

// Numbers the attractors of `values` (in parameter order) along the
// parameter, matching each value's attractors to the previous value's at
// `match_tolerance` (relative Hausdorff distance); the first value's
// attractors are numbered 1, 2, ... in their order. Returns the events, in
// parameter order.
std::vector<AttractorEvent> follow_attractors(std::vector<AttractorsAtValue>& values,
                                              double match_tolerance);

}  // namespace impactlab
