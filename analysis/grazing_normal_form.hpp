// The local normal form of the stroboscopic map at a grazing point, composed
// from the discontinuity map (discontinuity_map.hpp) and the virtual orbit's
// flow, its predicted scenario past the graze and the scaling of the orbits
// born there (docs/analysis.md, "Discontinuity map and normal form at a
// grazing point"; Nordmark 1991; Chin, Ott, Nusse & Grebogi 1994; di Bernardo,
// Budd, Champneys & Kowalczyk 2008, ch. 2 and 4).
//
// On the section through the touch (ωt ≡ ωt_g mod 2π, its state ξ = x − x_g
// and μ = p − p_g), one period of the virtual flow after the ZDM:
//
//   ξ ↦ N ξ + M μ                         h ≥ 0
//   ξ ↦ N ξ + M μ + E √(−h)               h < 0,   h = C ξ + d μ
//
// N = Φ₁Φ₂ the virtual orbit's monodromy from the touch, M its parameter
// vector, C = ∇h, d = ∂h/∂p, E = N L (L the ZDM's leading vector). The
// virtual fixed point's gap is g_μ μ, g_μ = C (I − N)⁻¹ M + d: the orbit
// impacts on the side sign(μ) = −sign(g_μ).
//
// Types, and the pure functions on them.
#pragma once

#include <complex>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <impactlab/analysis/discontinuity_map.hpp>

namespace impactlab {

// What the motion does just past a grazing point, on the side where the
// virtual orbit penetrates the wall.
enum class GrazingScenario {
  period_adding,             // stable orbits of one impact per n periods, n growing as μ → 0,
                             // their windows overlapping (no chaos between them)
  period_adding_with_chaos,  // those windows, separated by chaotic bands
  chaos,                     // a chaotic attractor at once, its size ∝ √|μ|
  stable_impacting_orbit,    // one stable impacting orbit, of the same period at every distance
  jump,                      // no attractor near the grazing orbit: an impact's kick drives a
                             // later iterate deeper into the wall, and the motion leaves for a
                             // distant attractor
  not_applicable,            // (the eigenvalue rule) complex multipliers, or a degenerate point
};

constexpr std::string_view to_string(GrazingScenario scenario) {
  switch (scenario) {
    case GrazingScenario::period_adding: return "period_adding";
    case GrazingScenario::period_adding_with_chaos: return "period_adding_with_chaos";
    case GrazingScenario::chaos: return "chaos";
    case GrazingScenario::stable_impacting_orbit: return "stable_impacting_orbit";
    case GrazingScenario::jump: return "jump";
    case GrazingScenario::not_applicable: return "not_applicable";
  }
  return "unknown";
}

// The normal form iterated at one distance past the graze, from its virtual
// fixed point: up to 4000 iterations, the last 1000 kept; periodic where the
// last 2p iterates repeat after p (p ≤ 400, to 1e-7 of the local scale),
// looked for every 50 iterations from the 250th (an even period whose halves
// impact alike, the slow approach to the half period's orbit near its period
// doubling, iterated on to the end first); chaotic where no period is found
// and the Lyapunov exponent is positive (above 0.02 after 1500 iterations
// ends the run early).
struct NormalFormAttractor {
  double distance = 0.0;      // μ = p − p_g (parameter units), on the impacting side
  std::string kind;           // periodic, chaotic, aperiodic (no period ≤ 400 and a
                              // Lyapunov exponent ≤ 0), escapes (leaves the graze's neighbourhood)
  int period = 0;             // periodic: iterations of the map (n forcing periods each)
  int impacts = 0;            // periodic: impacts per period; otherwise over the last 1000
  double max_impact_speed = 0.0;       // √(2a)·√(−h) at the deepest impact (gap rate units)
  std::vector<double> impact_speeds;   // periodic: one per impact; otherwise up to 64 of them
  double lyapunov = 0.0;      // per iteration
};

// The maximal period-n orbit of the normal form at μ: one impact (at the
// state `state`, deviation from x_g before the ZDM), then n − 1 iterations
// clear of the wall; its impact speed s solves s² + c_n s + g_μ μ = 0 (the
// root that vanishes with μ), c_n = C (I − Nⁿ)⁻¹ Nⁿ⁻¹ E.
struct MaximalOrbit {
  int n = 1;
  bool exists = false;       // the root is real and positive
  bool admissible = false;   // and the n − 1 free iterations keep h ≥ 0
  bool stable = false;       // every multiplier inside the unit circle
  double root = 0.0;         // s = √(−h) at the impact
  double impact_speed = 0.0; // √(2a) s (gap rate units)
  std::vector<double> state;
  std::vector<std::complex<double>> multipliers;  // of Nⁿ⁻¹ (N − E C / 2s)
};

// A further wall touched by the same virtual orbit (a symmetric orbit
// between two walls touches both at once): its ZDM and where it lies.
struct FurtherTouch {
  double phase = 0.0;            // rad, in [0, 2π): ωt of the touch
  double after = 0.0;            // s after the first touch
  int witness = -1;
  DiscontinuityMap map;          // the ZDM there (its h = ∇h·(y − x_j) + d_j μ)
  double gap_parameter = 0.0;    // d_j = ∂h/∂p there
};

struct GrazingNormalForm {
  bool available = false;
  std::string note;             // why not, where not available
  double parameter = 0.0;       // p_g
  double phase = 0.0;           // rad, in [0, 2π): ωt_g, the section the normal form lives on
  std::vector<double> state;    // x_g
  DiscontinuityMap map;         // the ZDM at the touch
  MonodromyMatrix linear;       // N (N × N)
  std::vector<std::complex<double>> eigenvalues;  // of N, largest modulus first
  std::vector<double> parameter_vector;  // M (state units per parameter unit)
  std::vector<double> gap_gradient;      // C = ∇h
  double gap_parameter = 0.0;            // d = ∂h/∂p (gap units per parameter unit)
  std::vector<double> root_vector;       // E = N L (state units per √gap)
  double gap_per_parameter = 0.0;        // g_μ: the virtual orbit's gap at the touch per unit μ
  int impacting_side = 0;                // ±1: the sign of μ where the virtual orbit penetrates
  // the first impact past the graze (of an orbit arriving on the virtual
  // orbit): V ≈ c √|μ|, c = √(2a |g_μ|); the chaotic attractor's impact
  // speeds and those of the period-adding orbits scale so too
  double root_coefficient = 0.0;
  // the local period-1 impacting orbit born at the graze (the branch whose
  // impact speed goes to zero): V₁ ≈ slope·|μ| on side period_one_side, slope
  // = √(2a)|g_μ|/|c₁|; always unstable near the graze (a multiplier ∝ 1/|μ|)
  double period_one_slope = std::numeric_limits<double>::quiet_NaN();
  int period_one_side = 0;
  std::vector<double> kick_gaps;  // e_k = C Nᵏ⁻¹ E, k = 1 … 24: an impact's effect on later gaps
  // with a real dominant eigenvalue λ₁: K = C P₁ E (P₁ its spectral
  // projector), the sign that decides whether the period-n orbits exist
  double dominant_product = std::numeric_limits<double>::quiet_NaN();
  GrazingScenario scenario = GrazingScenario::not_applicable;  // from the iterated normal form
  GrazingScenario rule = GrazingScenario::not_applicable;      // from λ₁ and the signs of e_k
  std::string other_side;           // the side without impacts: what remains there
  std::vector<int> period_sequence;  // periods of the periodic attractors, distance falling
  std::vector<NormalFormAttractor> attractors;  // 25 distances, |μ| falling
  // further touches (none for a single touch): the map is then the
  // composition, over the orbit, of each touch's ZDM and the virtual flow to
  // the next touch (segments[j]: flow and parameter vector from touch j, the
  // first being this form's own), iterated as such; the linear part N, M and
  // the first touch's E above are its own still, but the eigenvalue rule and
  // the maximal orbits (one touch) do not apply
  std::vector<FurtherTouch> further_touches;
  std::vector<MonodromyMatrix> segment_flows;
  std::vector<std::vector<double>> segment_parameter_vectors;
};

// The normal form at p_g from the system's local data; available false (with
// the note) where the ZDM is unavailable or the data are not finite.
GrazingNormalForm grazing_normal_form(const GrazingLocalFlow& local, double parameter);

// Its linear data and the eigenvalue rule only (the ZDM, N, M, C, d, E, g_μ,
// the side, the period-1 slope, e_k, K and `rule`), without iterating the
// map: no `scenario`, `other_side`, `attractors` or `period_sequence`. What
// a curve watches at each of its points.
GrazingNormalForm linear_normal_form(const GrazingLocalFlow& local, double parameter);

// The maximal period-n orbit at μ.
MaximalOrbit maximal_orbit(const GrazingNormalForm& form, int n, double mu);

// The normal form's attractor at μ, reached from its virtual fixed point.
NormalFormAttractor normal_form_attractor(const GrazingNormalForm& form, double mu);

// The scenario of the eigenvalue rule (Nordmark's square-root map, with λ₁
// the dominant multiplier): λ₁ real in (0, 1) and every e_k ≥ 0: period
// adding below λ₁ = 1/4, with chaos up to 2/3, chaos above; some e_k < 0, or
// λ₁ < 0: jump; complex multipliers: not_applicable.
GrazingScenario eigenvalue_rule(const GrazingNormalForm& form);

}  // namespace impactlab
