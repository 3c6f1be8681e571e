// How intricate a basins map is, from its label grid alone (no extra runs):
//
// * basin entropy S_b and boundary basin entropy S_bb (Daza, Wagemakers,
//   Georgeot, Guéry-Odelin, Sanjuán 2016, Sci. Rep. 6, 31416): the grid is
//   tiled by non-overlapping boxes of box_size × box_size grid points (the
//   points past the last whole box in either axis are left out); each box's
//   Gibbs entropy is −Σ_j p_j ln p_j over the shares p_j of its labels (nats);
//   S_b is its mean over all boxes, S_bb its mean over the N_b boxes holding
//   more than one label. S_bb > ln 2 is sufficient for a fractal boundary.
// * the uncertainty exponent α and the boundary's box dimension d = D − α
//   (D = 2) by the uncertainty method (Grebogi, McDonald, Ott, Yorke 1983):
//   a point is uncertain at scale k (grid units) when a neighbour k points away
//   along either axis (±k, inside the grid) has another label; f(k), the share
//   of uncertain points, goes as k^α; α is the least-squares slope of ln f
//   against ln k over k = 1, 2, 4, ... up to a quarter of the shorter side
//   (so that the neighbours exist for most points), with its standard error.
//
// Every label is its own class, 0 ("none found") included.
#pragma once

#include <vector>

namespace impactlab {

struct BasinMeasures {
  int box_size = 0;                    // ε: box side (grid points)
  int boxes = 0;                       // whole boxes that tile the grid
  int boundary_boxes = 0;              // N_b: boxes holding more than one label
  int labels = 0;                      // distinct labels in the grid (0 counted)
  double basin_entropy = 0.0;          // S_b (nats), 0 ≤ S_b ≤ ln(labels)
  double boundary_basin_entropy = 0.0; // S_bb (nats); nan without boundary boxes
  bool fractal_by_log2 = false;        // S_bb > ln 2: the boundary is fractal
  std::vector<int> scales;             // k (grid points)
  std::vector<double> uncertain_fraction;  // f(k), one per scale
  double uncertainty_exponent = 0.0;   // α; nan with fewer than 2 scales or f(1) = 0
  double uncertainty_exponent_error = 0.0;  // standard error of the slope; nan with < 3 scales
  double boundary_dimension = 0.0;     // d = 2 − α
};

// `labels` holds nx × ny labels, the first axis fastest (basins.csv's order).
// Throws std::invalid_argument when the sizes disagree or box_size is < 1 or
// larger than either side of the grid.
BasinMeasures basin_measures(const std::vector<int>& labels, int nx, int ny, int box_size);

}  // namespace impactlab
