// Painlevé paradox of a sliding Coulomb contact on a one-degree-of-freedom
// system: the normal force (or impulse) is the generalized load divided by
//     D = W_N - s μ W_T   (in units where the wall's normal Jacobian is positive),
// and when D <= 0 the rigid contact problem has no solution or several
// (Painlevé 1895; Brogliato, Nonsmooth Mechanics, §5.5). The simulator never
// divides by such a D: the model reports a typed diagnostic and stops.
#pragma once

namespace impactlab {

struct PainleveDiagnostic {
  double t;                    // time of the inconsistent configuration (s)
  int wall;                    // +1 / -1
  double denominator;          // D (dimensionless after scaling)
  double tangential_velocity;  // γ_T (m/s)
};

// D <= margin is treated as inconsistent: a denominator this small would turn
// the round-off of the load into an arbitrarily large force.
constexpr double painleve_margin = 1e-9;

constexpr bool is_painleve(double denominator) { return !(denominator > painleve_margin); }

}  // namespace impactlab
