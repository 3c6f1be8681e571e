// Truncated power series by automatic differentiation: the Taylor
// coefficients of the solution of x' = f(x, t) at t0, from the right-hand
// side written once over a number type.
//
// Recording: a right-hand side templated on its number type is run once per
// mode with TaylorVariable, which records each arithmetic operation and
// elementary function as a node of a TaylorTape (its decomposition into
// elementary operations; Jorba & Zou 2005, heyoka's "decomposition"). The
// witness functions of the mode are recorded on the same tape, so that their
// Taylor polynomials come with the state's.
//
// Evaluation: order by order, k = 0, 1, ..., p, every node's k-th coefficient
// from the lower ones of its operands (the classical recurrences: Cauchy
// product, the quotient rule, the coupled recurrence of sin and cos), and the
// state's coefficient k + 1 = (coefficient k of f) / (k + 1). Nodes that are
// polynomials of known degree in the time (the time itself, ωt) carry that
// degree, and the sums of the recurrences stop there: cos ωt costs O(1) per
// coefficient, its closed form. The tape has a fixed capacity and the stepper
// holds the coefficients, so nothing is allocated after construction.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>

namespace impactlab {

class TaylorTape;

// A number on a TaylorTape: a constant (no tape), or a node of the tape.
class TaylorVariable {
 public:
  TaylorVariable() = default;
  TaylorVariable(double constant) : constant_(constant) {}  // NOLINT: constants mix in freely
  TaylorVariable(TaylorTape* tape, int node) : tape_(tape), node_(node) {}

  [[nodiscard]] bool is_constant() const { return tape_ == nullptr; }
  [[nodiscard]] double constant() const { return constant_; }
  [[nodiscard]] TaylorTape* tape() const { return tape_; }
  [[nodiscard]] int node() const { return node_; }

 private:
  TaylorTape* tape_ = nullptr;
  int node_ = -1;
  double constant_ = 0.0;
};

enum class TaylorOp : std::uint8_t {
  constant,      // c
  state,         // component a of the state (its coefficients set by the integrator)
  time,          // t0 + h
  add,           // a + b
  subtract,      // a − b
  multiply,      // a · b
  divide,        // a / b
  affine,        // c1 · a + c (scalings and shifts of a node fold into one)
  sin,           // sin a, paired with the cos node b (computed together)
  cos,           // cos a, paired with the sin node b
  sign,          // the sign of a just after t0 (constant over a step)
};

struct TaylorNode {
  TaylorOp op = TaylorOp::constant;
  int a = -1, b = -1;  // operand nodes
  double c = 0.0;      // the constant of constant; the shift of affine
  int degree = 0;      // degree in h when the node is a polynomial in h, else unbounded
  bool live = false;   // reaches a derivative or a witness
  double c1 = 1.0;     // the factor of affine
};

class TaylorTape {
 public:
  static constexpr int max_nodes = 96;
  static constexpr int max_order = 32;
  static constexpr int unbounded = 1 << 20;  // the degree of a non-polynomial node
  static constexpr int max_dimension = 16;
  static constexpr int max_witness_count = 8;

  // coefficient storage of one tape, node-major: node n's coefficient k is
  // at n * (max_order + 1) + k; Real is double, or an extended-precision
  // type for references (Boost.Multiprecision)
  // (rows max_nodes.. hold j · a_j of each sin node's argument a: scratch
  // shared by the sin and cos recurrences)
  template <class Real = double>
  using CoefficientsOf = std::array<Real, 2 * max_nodes * (max_order + 1)>;
  using Coefficients = CoefficientsOf<double>;

  [[nodiscard]] bool recorded() const { return recorded_; }
  [[nodiscard]] int node_count() const { return node_count_; }
  [[nodiscard]] int dimension() const { return dimension_; }
  [[nodiscard]] int witness_count() const { return witness_count_; }

  // --- recording ---

  // Starts a recording with `dimension` state components: their variables.
  template <std::size_t Dimension>
  std::array<TaylorVariable, Dimension> begin(TaylorVariable& time) {
    static_assert(Dimension <= max_dimension);
    node_count_ = 0;
    dimension_ = static_cast<int>(Dimension);
    witness_count_ = 0;
    std::array<TaylorVariable, Dimension> x;
    for (std::size_t i = 0; i < Dimension; ++i)
      x[i] = TaylorVariable(this, push({TaylorOp::state, static_cast<int>(i), -1, 0.0, unbounded}));
    time = TaylorVariable(this, push({TaylorOp::time, -1, -1, 0.0, 1}));
    return x;
  }

  template <std::size_t Dimension>
  void set_derivatives(const std::array<TaylorVariable, Dimension>& dxdt) {
    for (std::size_t i = 0; i < Dimension; ++i) derivative_[i] = node_of(dxdt[i]);
  }

  void add_witness(const TaylorVariable& value) {
    if (witness_count_ == max_witness_count)
      throw std::length_error("taylor: more witnesses than the tape holds");
    witness_[witness_count_++] = node_of(value);
  }

  // Marks the nodes the derivatives and witnesses depend on; the others
  // (rates of witnesses, unused intermediates) are skipped in evaluation.
  void finish() {
    for (int n = 0; n < node_count_; ++n) nodes_[n].live = false;
    for (int i = 0; i < dimension_; ++i) nodes_[derivative_[i]].live = true;
    for (int j = 0; j < witness_count_; ++j) nodes_[witness_[j]].live = true;
    for (int i = 0; i < dimension_; ++i) nodes_[i].live = true;
    for (int n = node_count_ - 1; n >= 0; --n) {
      if (!nodes_[n].live) continue;
      const TaylorNode& node = nodes_[n];
      if (node.op == TaylorOp::state || node.op == TaylorOp::time || node.op == TaylorOp::constant)
        continue;
      nodes_[node.a].live = true;
      if (node.op == TaylorOp::add || node.op == TaylorOp::subtract ||
          node.op == TaylorOp::multiply || node.op == TaylorOp::divide ||
          node.op == TaylorOp::sin || node.op == TaylorOp::cos)
        nodes_[node.b].live = true;
    }
    // the nodes evaluated per order, in recording order (operands first); a
    // cos node is computed with its sin node
    sweep_count_ = 0;
    for (int n = dimension_; n < node_count_; ++n)
      if (nodes_[n].live && nodes_[n].op != TaylorOp::cos) sweep_[sweep_count_++] = n;
    recorded_ = true;
  }

  // the node of a variable; a constant becomes a constant node
  int node_of(const TaylorVariable& v) {
    if (!v.is_constant()) return v.node();
    return push({TaylorOp::constant, -1, -1, v.constant(), 0});
  }

  int push(const TaylorNode& node) {
    if (node_count_ == max_nodes)
      throw std::length_error("taylor: the right-hand side has more operations than the tape holds");
    nodes_[node_count_] = node;
    return node_count_++;
  }

  [[nodiscard]] const TaylorNode& node(int n) const { return nodes_[n]; }

  // the sin/cos pair of `a` (recorded once per argument): the sin node, the
  // cos node right after it
  int sin_cos_pair(int a) {
    for (int n = 0; n + 1 < node_count_; ++n)
      if (nodes_[n].op == TaylorOp::sin && nodes_[n].a == a) return n;
    const int s = push({TaylorOp::sin, a, -1, 0.0, unbounded});
    const int c = push({TaylorOp::cos, a, s, 0.0, unbounded});
    nodes_[s].b = c;
    return s;
  }

  // --- evaluation ---

  // The coefficients 0..order of every live node at (t0, x0): the state's
  // from the recurrence x_{k+1} = f_k / (k + 1).
  // With `signs_from_slope`, a sign node whose argument starts within
  // round-off of a zero (|a0| <= 1e-9 s · |a1|) takes the sign of a1, the
  // side the argument moves to, from the coefficients of the previous
  // evaluation at the same point (see signs_need_slope).
  template <class Real>
  void evaluate(const Real* x0, const Real& t0, int order, CoefficientsOf<Real>& c,
                bool signs_from_slope = false) const {
    using std::cos;
    using std::sin;
    constexpr int stride = max_order + 1;
    for (int i = 0; i < dimension_; ++i) c[i * stride] = x0[i];
    for (int k = 0; k <= order; ++k) {
      for (int i = 0; i < sweep_count_; ++i) {
        const int n = sweep_[i];
        const TaylorNode& node = nodes_[n];
        Real* out = &c[n * stride];
        const Real* a = node.a >= 0 ? &c[node.a * stride] : nullptr;
        const Real* b = node.b >= 0 ? &c[node.b * stride] : nullptr;
        switch (node.op) {
          case TaylorOp::state:
            break;
          case TaylorOp::constant:
            out[k] = k == 0 ? Real(node.c) : Real(0);
            break;
          case TaylorOp::time:
            out[k] = k == 0 ? t0 : k == 1 ? Real(1) : Real(0);
            break;
          case TaylorOp::add:
            out[k] = a[k] + b[k];
            break;
          case TaylorOp::subtract:
            out[k] = a[k] - b[k];
            break;
          case TaylorOp::affine:
            out[k] = k == 0 ? Real(node.c1 * a[0] + node.c) : Real(node.c1 * a[k]);
            break;
          case TaylorOp::multiply: {
            const int da = nodes_[node.a].degree, db = nodes_[node.b].degree;
            Real sum = 0;
            for (int j = std::max(0, k - db); j <= std::min(k, da); ++j) sum += a[j] * b[k - j];
            out[k] = sum;
            break;
          }
          case TaylorOp::divide: {
            // q = a / b: b0 q_k = a_k − Σ_{j=1..k} b_j q_{k−j}
            const int db = nodes_[node.b].degree;
            Real sum = a[k];
            for (int j = 1; j <= std::min(k, db); ++j) sum -= b[j] * out[k - j];
            out[k] = sum / b[0];
            break;
          }
          case TaylorOp::sin: {
            // s' = c a', c' = −s a': k s_k = Σ j a_j c_{k−j}, k c_k = −Σ j a_j s_{k−j}
            Real* cos_out = &c[node.b * stride];
            Real* ja = &c[(max_nodes + n) * stride];  // j · a_j
            if (k == 0) {
              out[0] = sin(a[0]);
              cos_out[0] = cos(a[0]);
              break;
            }
            ja[k] = k * a[k];
            const int da = nodes_[node.a].degree;
            Real s_sum = 0, c_sum = 0;
            for (int j = 1; j <= std::min(k, da); ++j) {
              s_sum += ja[j] * cos_out[k - j];
              c_sum += ja[j] * out[k - j];
            }
            out[k] = s_sum / k;
            cos_out[k] = -c_sum / k;
            break;
          }
          case TaylorOp::cos:
            break;  // computed with its sin node, which comes first
          case TaylorOp::sign:
            if (k > 0)
              out[k] = 0;
            else
              out[0] = signs_from_slope && near_zero(a) ? sign_of(a[1]) : sign_of(a[0]);
            break;
        }
      }
      if (k < order)
        for (int i = 0; i < dimension_; ++i)
          c[i * stride + k + 1] = c[derivative_[i] * stride + k] / (k + 1);
    }
  }

  // Whether a sign node of the last evaluation sits at a zero of its argument
  // that the argument is leaving for the other side (just after a slip
  // reversal): evaluate again with signs_from_slope.
  template <class Real>
  [[nodiscard]] bool signs_need_slope(const CoefficientsOf<Real>& c) const {
    for (int n = dimension_; n < node_count_; ++n) {
      const TaylorNode& node = nodes_[n];
      if (!node.live || node.op != TaylorOp::sign) continue;
      const Real* a = row(c, node.a);
      if (near_zero(a) && sign_of(a[1]) != sign_of(a[0])) return true;
    }
    return false;
  }

  // the coefficients of state component i and of witness j
  template <class Real>
  [[nodiscard]] static const Real* row(const CoefficientsOf<Real>& c, int node) {
    return &c[node * (max_order + 1)];
  }
  [[nodiscard]] int witness_node(int j) const { return witness_[j]; }

 private:
  template <class Real>
  static Real sign_of(const Real& v) { return v > 0 ? Real(1) : v < 0 ? Real(-1) : Real(0); }
  // a zero of the argument within 1e-9 s of t0 (its coefficients a0, a1)
  template <class Real>
  static bool near_zero(const Real* a) {
    using std::fabs;
    return fabs(a[0]) <= 1e-9 * fabs(a[1]);
  }

  std::array<TaylorNode, max_nodes> nodes_{};
  std::array<int, max_dimension> derivative_{};
  std::array<int, max_witness_count> witness_{};
  std::array<int, max_nodes> sweep_{};  // live nodes, evaluation order
  int sweep_count_ = 0;
  int node_count_ = 0;
  int dimension_ = 0;
  int witness_count_ = 0;
  bool recorded_ = false;
};

namespace detail {

inline TaylorTape* tape_of(const TaylorVariable& a, const TaylorVariable& b) {
  return a.tape() != nullptr ? a.tape() : b.tape();
}

inline TaylorVariable binary(TaylorOp op, const TaylorVariable& a, const TaylorVariable& b,
                             int degree) {
  TaylorTape* tape = tape_of(a, b);
  const int na = tape->node_of(a), nb = tape->node_of(b);
  return {tape, tape->push({op, na, nb, 0.0, std::min(degree, TaylorTape::unbounded)})};
}

inline int degree_of(const TaylorVariable& v) {
  return v.is_constant() ? 0 : v.tape()->node(v.node()).degree;
}

// factor · v + shift, folded into v's own affine node where v is one
inline TaylorVariable affine(const TaylorVariable& v, double factor, double shift) {
  TaylorTape* tape = v.tape();
  const TaylorNode& node = tape->node(v.node());
  int a = v.node();
  double c1 = factor, c0 = shift;
  if (node.op == TaylorOp::affine) {
    a = node.a;
    c1 = factor * node.c1;
    c0 = factor * node.c + shift;
  }
  if (c1 == 1.0 && c0 == 0.0) return {tape, a};
  TaylorNode folded{TaylorOp::affine, a, -1, c0, tape->node(a).degree};
  folded.c1 = c1;
  return {tape, tape->push(folded)};
}

}  // namespace detail

// --- arithmetic: constants fold, a constant operand makes an affine node ---

inline TaylorVariable operator+(const TaylorVariable& a, const TaylorVariable& b) {
  if (a.is_constant() && b.is_constant()) return a.constant() + b.constant();
  if (a.is_constant() || b.is_constant()) {
    const TaylorVariable& v = a.is_constant() ? b : a;
    const double c = a.is_constant() ? a.constant() : b.constant();
    return detail::affine(v, 1.0, c);
  }
  return detail::binary(TaylorOp::add, a, b, std::max(detail::degree_of(a), detail::degree_of(b)));
}

inline TaylorVariable operator*(const TaylorVariable& a, const TaylorVariable& b) {
  if (a.is_constant() && b.is_constant()) return a.constant() * b.constant();
  if (a.is_constant() || b.is_constant()) {
    const TaylorVariable& v = a.is_constant() ? b : a;
    const double c = a.is_constant() ? a.constant() : b.constant();
    return detail::affine(v, c, 0.0);
  }
  return detail::binary(TaylorOp::multiply, a, b, detail::degree_of(a) + detail::degree_of(b));
}

inline TaylorVariable operator-(const TaylorVariable& a) { return -1.0 * a; }

inline TaylorVariable operator-(const TaylorVariable& a, const TaylorVariable& b) {
  if (a.is_constant() && b.is_constant()) return a.constant() - b.constant();
  if (b.is_constant()) return a + (-b.constant());
  if (a.is_constant()) return (-b) + a.constant();
  return detail::binary(TaylorOp::subtract, a, b,
                        std::max(detail::degree_of(a), detail::degree_of(b)));
}

inline TaylorVariable operator/(const TaylorVariable& a, const TaylorVariable& b) {
  if (b.is_constant()) return a * (1.0 / b.constant());
  const int degree = detail::degree_of(b) == 0 ? detail::degree_of(a) : TaylorTape::unbounded;
  return detail::binary(TaylorOp::divide, a, b, degree);
}

inline TaylorVariable& operator+=(TaylorVariable& a, const TaylorVariable& b) { return a = a + b; }
inline TaylorVariable& operator-=(TaylorVariable& a, const TaylorVariable& b) { return a = a - b; }
inline TaylorVariable& operator*=(TaylorVariable& a, const TaylorVariable& b) { return a = a * b; }
inline TaylorVariable& operator/=(TaylorVariable& a, const TaylorVariable& b) { return a = a / b; }

// --- elementary functions, found by argument-dependent lookup from a
// right-hand side that calls them unqualified ---

inline TaylorVariable sin(const TaylorVariable& a) {
  if (a.is_constant()) return std::sin(a.constant());
  return {a.tape(), a.tape()->sin_cos_pair(a.node())};
}

inline TaylorVariable cos(const TaylorVariable& a) {
  if (a.is_constant()) return std::cos(a.constant());
  return {a.tape(), a.tape()->sin_cos_pair(a.node()) + 1};
}

// core/fast_trig.hpp's names: the same functions on a series
inline TaylorVariable sin_angle(const TaylorVariable& a) { return sin(a); }
inline TaylorVariable cos_phase(const TaylorVariable& a) { return cos(a); }

// The sign of a (−1, 0, +1), constant over a step: the systems end a step at
// every zero of a quantity whose sign they use (slip reversals are events).
inline TaylorVariable sign(const TaylorVariable& a) {
  if (a.is_constant()) return a.constant() > 0.0 ? 1.0 : a.constant() < 0.0 ? -1.0 : 0.0;
  return {a.tape(), a.tape()->push({TaylorOp::sign, a.node(), -1, 0.0, 0})};
}

inline TaylorVariable fabs(const TaylorVariable& a) { return sign(a) * a; }

}  // namespace impactlab
