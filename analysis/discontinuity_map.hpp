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

// What the system gives at a located grazing point (ContinuationProblem::
// grazing_flow): the touch, the local geometry of the gap, the reset, the
// virtual orbit's flow split at the touch, and the parameter derivatives. N
// is the tangent dimension; times are seconds since the section the orbit
// was solved on (phase `section_phase`).
struct GrazingLocalFlow {
  bool completed = false;
  std::string failure;        // why not completed
  std::vector<double> state;  // x_g: the N tangent components at the touch
  double time = 0.0;          // t_g since the section (s)
  double section_phase = 0.0; // rad: the section ωt ≡ section_phase the orbit was solved on
  double phase = 0.0;         // rad: ωt_g, the forcing phase of the touch (unreduced)
  double omega = 0.0;         // forcing frequency (rad/s)
  double period = 0.0;        // nT (s)
  int witness = -1;           // the touched wall's witness
  double gap = 0.0, gap_rate = 0.0;  // h and ḣ at the touch (zero to the solver's tolerance)
  double gap_acceleration = 0.0;     // a = ḧ (gap unit / s²), > 0 where the flight curves away
  double gap_jerk = 0.0;             // b = h⃛ (gap unit / s³)
  std::vector<double> gap_gradient;  // ∇h (N)
  std::vector<double> rate_gradient; // ∇ḣ (N)
  std::vector<double> field;         // f(x_g, t_g) (N)
  MonodromyMatrix field_jacobian;    // J = ∂f/∂x at the touch (N × N)
  MonodromyMatrix reset_jacobian;    // G = ∂g/∂x of an impact at the touch (N × N)
  MonodromyMatrix to_touch;          // Φ₁: ∂x(t_g)/∂x(section), the virtual flow
  MonodromyMatrix from_touch;        // Φ₂: ∂x(section + nT)/∂x(t_g), the virtual flow
  // ∂/∂p at a fixed state and fixed forcing phases (the parameter step and
  // stencil in docs/analysis.md):
  std::vector<double> touch_parameter_derivative;  // B₁ = ∂x(t_g)/∂p from the section state
  std::vector<double> image_parameter_derivative;  // M_p = ∂Pⁿ/∂p of the section map
  double gap_parameter_derivative = 0.0;            // h_p = ∂h/∂p at x_g, phase ωt_g
  double parameter_step = 0.0;                      // the stencil's step in p
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

// The ZDM's coefficients from the local data (available false, with the
// reason, where a ≤ 0 or the reset or the gap's gradients are degenerate).
DiscontinuityMap discontinuity_map(const GrazingLocalFlow& local);

// D(y) − y for the deviation y − x_g (and the gap h(y) = ∇h·(y − x_g) +
// gap_offset, the parameter's direct share): the leading order alone, or
// with the next order.
std::vector<double> discontinuity_jump(const DiscontinuityMap& map,
                                       const std::vector<double>& deviation, bool next_order,
                                       double gap_offset = 0.0);

}  // namespace impactlab
