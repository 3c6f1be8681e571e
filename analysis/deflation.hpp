// Deflation of the roots already found (Farrell, Birkisson & Funke 2015,
// "Deflation techniques for finding distinct solutions of nonlinear partial
// differential equations", SIAM J. Sci. Comput. 37(4)): Newton's method on
//     G(x) = M(x) F(x),   M(x) = Π_i (1/|x − r_i|^p + σ)
// in place of F(x) = 0 finds a root of F other than the known r_i, because
// G does not vanish at r_i (M grows like |x − r_i|^−p there) and has every
// other root of F.
//
// p = 2: the paper's choice; any p ≥ 1 removes a simple root, and the even
// power keeps M smooth (|x − r|² is a polynomial). σ = 1: far from every
// known root M → 1, so G → F and Newton behaves as it would undeflated; with
// σ = 0, M → 0 as |x| → ∞ and the deflated iteration can "converge" by running
// off to infinity. Both act on the distance in the state's own units (on the
// tangent space's N components), so a root closer than about one unit to a
// known one is pushed on hardest.
//
// The deflated Newton step is the undeflated one scaled (Sherman–Morrison on
// J_G = M (J_F + F ∇(log M)ᵀ)):
//     δ_G = δ_F / (1 − ∇(log M) · δ_F),
//     ∇ log M = Σ_i −p (x − r_i) |x − r_i|^(−p−2) / (|x − r_i|^(−p) + σ).
// With no known roots M = 1 and δ_G = δ_F exactly.
#pragma once

#include <span>
#include <vector>

namespace impactlab {

struct Deflation {
  double power = 2.0;  // p: the order of the pole put at each known root
  double shift = 1.0;  // σ: what M tends to far from the known roots
  std::vector<std::vector<double>> roots;  // r_i, each on the tangent space (N components)
};

// M(x) = Π_i (1/|x − r_i|^p + σ); 1 with no roots, +∞ at a known root.
double deflation_factor(const Deflation& deflation, std::span<const double> x);

// ∇ log M at x, into `gradient` (x's size).
void deflation_log_gradient(const Deflation& deflation, std::span<const double> x,
                            std::span<double> gradient);

// The deflated Newton step from the undeflated `step` δ_F at x, in place:
// δ_F / (1 − ∇(log M) · δ_F). False, the step left as it was, where the
// denominator is zero or not finite (x on a known root).
bool deflate_step(const Deflation& deflation, std::span<const double> x, std::span<double> step);

}  // namespace impactlab
