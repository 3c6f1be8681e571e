// Deflation of the roots already found (Farrell, Birkisson & Funke 2015,
// "Deflation techniques for finding distinct solutions of nonlinear partial
// differential equations", SIAM J. Sci. Comput. 37(4)): Newton's method on
//     G(x) = M(x) F(x),   M(x) = Π_i (1/d_i(x)^p + σ),   d_i(x) = |x − r_i| / ρ
// in place of F(x) = 0 finds a root of F other than the known r_i, because
// G does not vanish at r_i (M grows like d_i^−p there) and has every other
// root of F.
//
// p = 2: the paper's choice; any p ≥ 1 removes a simple root, and the even
// power keeps M smooth (|x − r|² is a polynomial). σ = 1: far from every
// known root M → 1, so G → F and Newton behaves as it would undeflated; with
// σ = 0, M → 0 as |x| → ∞ and the deflated iteration can "converge" by running
// off to infinity. ρ (in the state's units, on the tangent space's N
// components) is the distance within which a known root repels: the paper's
// ρ = 1 is about the size of the whole box of starts of the oscillators here
// (the ball's heights are centimetres, its speeds about 1 m/s), and there M
// distorts |G| everywhere: on the bouncing ball at its default amplitude,
// 100 starts from y ∈ [0.02, 0.08] m, ẏ ∈ [−1, 1] m/s, ρ = 1 found 3 of the 6
// period-1 orbits that plain Newton finds (97 starts stopped at a spurious
// minimum of M|F| along Newton's direction); ρ = 0.1 found all 6, none twice.
//
// The deflated Newton step is the undeflated one scaled (Sherman–Morrison on
// J_G = M (J_F + F ∇(log M)ᵀ)):
//     δ_G = δ_F / (1 − ∇(log M) · δ_F),
//     ∇ log M = Σ_i −p (x − r_i) d_i^(−p−2) / (ρ² (d_i^(−p) + σ)).
// With no known roots M = 1 and δ_G = δ_F exactly.
#pragma once

#include <span>
#include <vector>

namespace impactlab {

struct Deflation {
  double power = 2.0;  // p: the order of the pole put at each known root
  double shift = 1.0;  // σ: what M tends to far from the known roots
  double radius = 0.1; // ρ: the distance unit of M (the state's units)
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
