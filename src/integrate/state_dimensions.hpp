// The state types of the built-in oscillators and of their variational
// equations, for which the steppers that take their right-hand side as a
// view (integrate/state_rhs.hpp), and rkf78's constructor, are compiled
// once, in the engine: {q, q̇}, {θ, θ̇, W_f}, Model P's {θ, θ̇, W_f,
// θ̇_release}, the rigid pendulum's {θ, θ̇, φ̇, φ, W_f}, and the variational
// states (analysis/variational.hpp: 6 and 7 components, the rigid
// pendulum's 9 and 14, a four-state model file's 20). X(N) is applied to
// each N of std::array<double, N>; other state types compile the steppers
// where they are used.
#pragma once

#include <array>

#define IMPACTLAB_FOR_EACH_STATE_DIMENSION(X) X(2) X(3) X(4) X(5) X(6) X(7) X(9) X(14) X(20)
