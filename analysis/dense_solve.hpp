// The dense linear problems of continuation on run-time-size matrices,
// compiled once (analysis/dense_solve.cpp): Eigen's LU with full pivoting and
// its Jacobi SVD cost seconds of compile in every unit that instantiates
// them. The results are those of the same Eigen calls made in place.
#pragma once

#include <Eigen/Core>

namespace impactlab {

// x with A x = b, from Eigen::FullPivLU (A square; a singular A gives what
// FullPivLU::solve gives: a solution where one exists, else non-finite or
// inexact values the caller checks)
Eigen::VectorXd full_pivot_lu_solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b);

// The right singular vector of A's smallest singular value, of unit length:
// the last column of V from Eigen::JacobiSVD with the full V (a null vector of
// a rank-deficient A, with the sign the SVD gives it)
Eigen::VectorXd last_right_singular_vector(const Eigen::MatrixXd& a);

}  // namespace impactlab
