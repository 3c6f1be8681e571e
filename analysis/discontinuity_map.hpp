// Nordmark's zero-time discontinuity map (ZDM) at a grazing point, to leading
// and next order, from the vector field, the wall's gap and the reset
// (docs/analysis.md, "Discontinuity map and normal form at a grazing point").
//
// At the touch x_g, time t_g, the gap h of the touched wall has h = 0, ḣ = 0
// and ḧ = a > 0 (the flight curves away from the wall). A state y at t_g of
// the *virtual* flow (the wall's contacts suppressed) with gap h(y) < 0 has
// in fact hit the wall shortly before or after t_g, with the normal speed
// V ≈ √(−2a h); the ZDM maps y to the state the real flow (with the impact)
// has at the same time t_g:
//
//   D(y) = y                                         h(y) ≥ 0
//   D(y) = y + L √(−h(y)) + Q h(y) + O(|h|^{3/2})    h(y) < 0
//   L = −√(2a) W,   Q = 2 J W − (2b / 3a) W
//
// with W = (G − I) u the reset's jump per unit of the normal velocity before
// it (x⁺ − x⁻ = W ḣ⁻: G = ∂g/∂x the reset's Jacobian at the touch, u a
// tangent vector with ∇h·u = 0 and ∇ḣ·u = 1), J = ∂f/∂x at the touch and
// b = h⃛ the third time derivative of the gap along the orbit. Derivation:
// the impact happens s ≈ −√(−2h/a) before t_g (exactly: V = √(−2ah) +
// (2b/3a) h + O(h^{3/2})), the reset adds −W V, and flowing back over s
// changes that jump by −s J(−W V) = 2h J W. The law is assumed linear in the
// normal velocity near zero (v⁺ = −r v⁻, a Newton impact; every built-in
// oscillator's law is).
#pragma once

#include <string>
#include <vector>

#include <impactlab/analysis/floquet_multipliers.hpp>

namespace impactlab {

// One touch of the virtual orbit (the touched wall's contacts suppressed
// near it): where a wall gap has a zero minimum, its local geometry and the
// reset of an impact there. N is the tangent dimension.
struct GrazingTouch {
  int witness = -1;           // the touched wall's witness
  double time = 0.0;          // since the section the orbit was solved on (s)
  double phase = 0.0;         // rad: ωt of the touch (unreduced)
  std::vector<double> state;  // x_g: the N tangent components at the touch
  double gap = 0.0, gap_rate = 0.0;  // h and ḣ at the touch (zero to the solver's tolerance)
  double gap_acceleration = 0.0;     // a = ḧ (gap unit / s²), > 0 where the flight curves away
  double gap_jerk = 0.0;             // b = h⃛ (gap unit / s³)
  std::vector<double> gap_gradient;  // ∇h (N)
  std::vector<double> rate_gradient; // ∇ḣ (N)
  MonodromyMatrix field_jacobian;    // J = ∂f/∂x at the touch (N × N)
  MonodromyMatrix reset_jacobian;    // G = ∂g/∂x of an impact at the touch (N × N)
  double gap_parameter_derivative = 0.0;  // h_p = ∂h/∂p at x_g and the touch's phase
};

// The virtual flow from one touch to the next.
struct GrazingSegment {
  MonodromyMatrix flow;                      // ∂x(end)/∂x(start)
  std::vector<double> parameter_derivative;  // ∂x(end)/∂p at a fixed start state and fixed phases
};

// What the system gives at a located grazing point (ContinuationProblem::
// grazing_flow): the touches of the virtual orbit through it, the located
// one first and the others (another wall touched at once: a symmetric orbit
// between two walls) in their order along the orbit, and the flow from each
// touch to the next (the last segment back to the first touch, one orbit on).
struct GrazingLocalFlow {
  bool completed = false;
  std::string failure;         // why not completed
  double section_phase = 0.0;  // rad: the section ωt ≡ section_phase the orbit was solved on
  double omega = 0.0;          // forcing frequency (rad/s)
  double period = 0.0;         // nT (s)
  double parameter_step = 0.0; // the parameter stencil's step
  std::vector<GrazingTouch> touches;
  std::vector<GrazingSegment> segments;  // segments[j]: touches[j] to the next touch
};

struct DiscontinuityMap {
  bool available = false;
  std::string failure;
  std::vector<double> state;          // x_g
  std::vector<double> gap_gradient;   // ∇h: h(y) ≈ ∇h·(y − x_g)
  double gap_acceleration = 0.0;      // a
  double gap_jerk = 0.0;              // b
  std::vector<double> jump;           // W: x⁺ − x⁻ = W ḣ⁻ (state units per gap rate)
  std::vector<double> leading;        // L = −√(2a) W (state units per √gap)
  std::vector<double> next;           // Q = 2 J W − (2b/3a) W (state units per gap)
};

// The ZDM's coefficients at a touch (available false, with the reason, where
// a ≤ 0 or the reset or the gap's gradients are degenerate).
DiscontinuityMap discontinuity_map(const GrazingTouch& touch);

// D(y) − y for the deviation y − x_g (and the gap h(y) = ∇h·(y − x_g) +
// gap_offset, the parameter's direct share): the leading order alone, or
// with the next order.
std::vector<double> discontinuity_jump(const DiscontinuityMap& map,
                                       const std::vector<double>& deviation, bool next_order,
                                       double gap_offset = 0.0);

}  // namespace impactlab
