// Basins of attraction: every initial condition of a 2D grid is run from the
// scene's state with the grid's two keys set (typically initial.theta ×
// initial.theta_dot; the sweep machinery of analysis/sweep.hpp with
// SweepPlan::follow_attractor false), and classified by the attractor it
// settles on.
//
// An attractor is told by its period p (section-map iterations), impacts per
// forcing period, contact, and a canonical point of its section cycle: the
// lexicographically smallest (q, then q̇) of the last p section points, so that
// two different period-1 orbits are told apart and the p points of one cycle
// are one attractor. Points whose canonical points lie within `tolerance` ×
// (1 + |x|) of an attractor's (and whose period, impacts and contact agree)
// settle on it. Attractors are numbered 1, 2, ... by first appearance in the
// grid order (the first key fastest), so the numbering does not depend on
// threads or ranks; 0 is "none found" (no period up to max_period, or a run
// that stopped early).
#pragma once

#include <array>
#include <vector>

#include <impactlab/analysis/sweep.hpp>

namespace impactlab {

struct Attractor {
  int id = 0;                      // 1, 2, ... (0: none found)
  int period = 0;                  // forcing periods of the cycle on the section
  double impacts_per_period = 0.0; // impacts per forcing period
  bool contact = false;            // a contact (sticking/sliding) phase
  std::array<double, 2> point{};   // canonical section point (q, q̇)
  int basin_points = 0;            // grid points that settle on it
};

struct BasinMap {
  std::vector<int> attractor;         // per record, in the order given: its attractor's id
  std::vector<Attractor> attractors;  // by id (attractors[k].id == k + 1)
  int unclassified = 0;               // points of attractor 0
};

// The canonical point of a record's cycle (nullopt: no period found, or the
// run stopped early).
std::optional<std::array<double, 2>> canonical_point(const SweepRecord& record);

// Classifies the records, given in grid order (first key fastest).
BasinMap identify_attractors(const std::vector<const SweepRecord*>& records, double tolerance);

}  // namespace impactlab
