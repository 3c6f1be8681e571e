// A polynomial's value at a point: the Taylor stepper's dense output and
// the root refinement's evaluations (integrate/monotone_root.hpp).
#pragma once

namespace impactlab {

// Σ_{j=0..degree} c_j h^j by Horner's scheme in h² on the even and the odd
// coefficients: two independent chains of half the length (a Taylor step's
// end state and every evaluation of a root refinement wait for it); zero
// for a negative degree. Real: double, an extended-precision type, or
// LaneNumber (integrate/lane_number.hpp), whose lanes each get the double
// sum of their own coefficients to the bit.
template <class Coefficients, class Real>
Real polynomial_at(const Coefficients& c, int degree, const Real& h) {
  if (degree < 0) return Real(0);  // a derivative past the degree
  const Real h2 = h * h;
  Real even = 0, odd = 0;
  int j = degree;
  if (j % 2 == 0) even = c[j--];
  for (; j >= 1; j -= 2) {
    odd = odd * h2 + c[j];
    even = even * h2 + c[j - 1];
  }
  return even + h * odd;
}

}  // namespace impactlab
