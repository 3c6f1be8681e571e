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
//
// Compilation (TaylorTape::compile, when a recording finishes): the live
// nodes become a short list of instructions with their rows resolved, in
// three phases. Only the nodes between the state and its derivatives must
// go order by order; the functions of t alone (ωt, cos ωt, g_e(t)) before
// them and the witnesses after them go node by node, each instruction's
// recurrence a loop over all orders. Sums, scalings and products used once
// by a sum fold into one linear instruction, so the pendulum's free flight
// is two instructions per order (sin/cos of θ, and θ̈ = c1 θ̇ + c2 g_e sin θ)
// instead of twelve nodes.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <type_traits>

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

// The recurrences of the compiled tape (TaylorTape::compile): one per kind
// of node, the sums and scalings fused into linear combinations.
enum class TaylorKernel : std::uint8_t {
  constant,  // c, then zeros
  time,      // t0, 1, then zeros
  linear,    // shift + Σ factor_i · term_i (add, subtract, affine and their chains)
  multiply,  // Cauchy product, truncated at the operands' degrees
  divide,    // quotient recurrence
  sin_cos,   // the coupled recurrence of sin a and cos a
  sign,      // the sign of a just after t0, then zeros
};

// A term of a linear instruction: factor · a, or factor · a · b (a product
// used by this sum only, folded into it); a and b are where their rows start
// in the coefficient array.
struct TaylorTerm {
  int a = -1, b = -1;
  int a_degree = 0, b_degree = 0;  // degrees in h of a and b (products)
  double factor = 0.0;
};

// One instruction of the compiled tape: a node's recurrence with its operand
// rows resolved (out, a, b, scratch, rate: where the rows start in the
// node-major coefficient array, so that no index is multiplied while
// evaluating).
struct TaylorInstruction {
  TaylorKernel kernel = TaylorKernel::constant;
  int out = -1;                    // the node's row (sin_cos: the sin row)
  int a = -1, b = -1;              // operand rows (sin_cos: a the argument, b the cos row)
  int a_degree = 0, b_degree = 0;  // their degrees in h (TaylorTape::unbounded if not polynomials)
  int scratch = -1;                // sin_cos: the row of j · a_j
  int rate = -1;                   // sin_cos of a state component: its derivative's row
  int first_term = 0, term_count = 0;  // linear: its terms in the tape's term list
  double shift = 0.0;              // linear: added at order 0; constant: the value
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
    compile();
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
  //
  // The compiled program (compile()) runs in three phases: the functions of
  // t alone (ωt, cos ωt, constants) node by node, all orders of one before
  // the next; the nodes between the state and its derivatives order by order
  // (coefficient k of each needs the state's k, which needs the
  // derivatives' k − 1); the rest (witnesses) node by node again. Node by
  // node, an instruction is dispatched once per step and its recurrence is
  // a loop over the orders.
  template <class Real>
  void evaluate(const Real* x0, const Real& t0, int order, CoefficientsOf<Real>& c,
                bool signs_from_slope = false) const {
    constexpr int stride = max_order + 1;
    for (int i = 0; i < dimension_; ++i) c[i * stride] = x0[i];
    const Context<Real> context{c.data(), t0, signs_from_slope};
    for (int i = 0; i < phase_end_[0]; ++i) run(program_[i], 0, order, context);
    for (int k = 0; k <= order; ++k) {
      for (int i = phase_end_[0]; i < phase_end_[1]; ++i) run(program_[i], k, k, context);
      if (k < order)
        for (int i = 0; i < dimension_; ++i)
          c[i * stride + k + 1] = c[derivative_offset_[i] + k] * reciprocal<Real>(k + 1);
    }
    for (int i = phase_end_[1]; i < program_count_; ++i) run(program_[i], 0, order, context);
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
  // what the kernels of one evaluation share: the coefficients (node-major,
  // max_order + 1 per row), the step's start time
  template <class Real>
  struct Context {
    Real* c;
    Real t0;
    bool signs_from_slope;
    [[nodiscard]] Real* row(int offset) const { return c + offset; }
  };

  // The operands of a node (none, a, or a and b); sin and cos: the argument.
  static int operand_count(TaylorOp op) {
    switch (op) {
      case TaylorOp::constant:
      case TaylorOp::state:
      case TaylorOp::time:
        return 0;
      case TaylorOp::affine:
      case TaylorOp::sin:
      case TaylorOp::cos:
      case TaylorOp::sign:
        return 1;
      default:
        return 2;
    }
  }
  // where node n's row starts in the coefficient array (−1: no node)
  static int offset(int n) { return n >= 0 ? n * (max_order + 1) : -1; }
  static bool is_linear(TaylorOp op) {
    return op == TaylorOp::add || op == TaylorOp::subtract || op == TaylorOp::affine;
  }

  // Compiles the live nodes into program_: phase 0, the nodes that do not
  // depend on the state; phase 1, the nodes the derivatives need that do;
  // phase 2, the others (witnesses). A sum, scaling or product used once, by
  // a sum or scaling of the same phase, and neither a derivative nor a
  // witness, is folded into its user (so −(d x1 + m l g_e sin x0) / (m l²)
  // is one instruction of two terms, one a product, not four nodes), and its
  // row is not written.
  void compile() {
    std::array<bool, max_nodes> on_state{}, needed{}, kept{};
    std::array<int, max_nodes> phase{}, uses{};
    for (int n = 0; n < node_count_; ++n) {
      const TaylorNode& node = nodes_[n];
      const int operands = operand_count(node.op);
      on_state[n] = node.op == TaylorOp::state || (operands >= 1 && on_state[node.a]) ||
                    (operands == 2 && on_state[node.b]);
    }
    for (int i = 0; i < dimension_; ++i) needed[derivative_[i]] = true;
    for (int n = node_count_ - 1; n >= 0; --n) {
      if (!needed[n]) continue;
      const TaylorNode& node = nodes_[n];
      if (node.op == TaylorOp::cos) needed[node.b] = true;  // computed with its sin node
      const int operands = operand_count(node.op);
      if (operands >= 1) needed[node.a] = true;
      if (operands == 2) needed[node.b] = true;
    }
    for (int n = 0; n < node_count_; ++n) {
      const TaylorNode& node = nodes_[n];
      phase[n] = !on_state[n] ? 0 : needed[n] ? 1 : 2;
      if (!node.live || node.op == TaylorOp::state || node.op == TaylorOp::cos) continue;
      const int operands = operand_count(node.op);
      if (operands >= 1) ++uses[node.a];
      if (operands == 2) ++uses[node.b];
    }
    for (int i = 0; i < dimension_; ++i) uses[derivative_[i]] += 2;  // never folded
    for (int j = 0; j < witness_count_; ++j) uses[witness_[j]] += 2;
    auto folded = [&](int operand, int user) {
      const TaylorOp op = nodes_[operand].op;
      return (is_linear(op) || op == TaylorOp::multiply) && uses[operand] == 1 &&
             phase[operand] == phase[user];
    };
    for (int n = dimension_; n < node_count_; ++n) {
      const TaylorNode& node = nodes_[n];
      kept[n] = node.live && node.op != TaylorOp::cos;
      if (node.live && is_linear(node.op)) {
        if (folded(node.a, n)) kept[node.a] = false;
        if (node.op != TaylorOp::affine && folded(node.b, n)) kept[node.b] = false;
      }
    }
    for (int i = 0; i < dimension_; ++i) derivative_offset_[i] = offset(derivative_[i]);
    program_count_ = 0;
    term_count_ = 0;
    for (int p = 0; p < 3; ++p) {
      for (int n = dimension_; n < node_count_; ++n)
        if (kept[n] && phase[n] == p) program_[program_count_++] = instruction(n, kept);
      if (p < 2) phase_end_[p] = program_count_;
    }
  }

  TaylorInstruction instruction(int n, const std::array<bool, max_nodes>& kept) {
    const TaylorNode& node = nodes_[n];
    TaylorInstruction in;
    in.out = offset(n);
    in.a = offset(node.a);
    in.b = offset(node.b);
    in.a_degree = node.a >= 0 ? nodes_[node.a].degree : 0;
    in.b_degree = node.b >= 0 ? nodes_[node.b].degree : 0;
    switch (node.op) {
      case TaylorOp::constant:
        in.kernel = TaylorKernel::constant;
        in.shift = node.c;
        break;
      case TaylorOp::time:
        in.kernel = TaylorKernel::time;
        break;
      case TaylorOp::multiply:
        in.kernel = TaylorKernel::multiply;
        break;
      case TaylorOp::divide:
        in.kernel = TaylorKernel::divide;
        break;
      case TaylorOp::sin:
        in.kernel = TaylorKernel::sin_cos;
        in.scratch = offset(max_nodes + n);
        if (node.a < dimension_) in.rate = offset(derivative_[node.a]);
        break;
      case TaylorOp::sign:
        in.kernel = TaylorKernel::sign;
        break;
      default:  // add, subtract, affine
        in.kernel = TaylorKernel::linear;
        in.first_term = term_count_;
        add_terms(n, 1.0, true, kept, in);
        // products last: they hold this order's newest coefficients. A
        // stable partition in place by rotations, not std::stable_partition,
        // whose temporary buffer is a heap allocation: a mode's tape is
        // recorded inside the event loop, which allocates nothing.
        {
          TaylorTerm* boundary = &terms_[in.first_term];
          for (TaylorTerm* t = boundary; t != &terms_[term_count_]; ++t)
            if (t->b < 0) std::rotate(boundary++, t, t + 1);
        }
        break;
    }
    return in;
  }

  // adds factor · node n to the linear instruction, expanding n where it is
  // the instruction's own node or one folded into it
  void add_terms(int n, double factor, bool own, const std::array<bool, max_nodes>& kept,
                 TaylorInstruction& in) {
    const TaylorNode& node = nodes_[n];
    if (own || (!kept[n] && is_linear(node.op))) {
      if (node.op == TaylorOp::affine) {
        in.shift += factor * node.c;
        add_terms(node.a, factor * node.c1, false, kept, in);
      } else {
        add_terms(node.a, factor, false, kept, in);
        add_terms(node.b, node.op == TaylorOp::subtract ? -factor : factor, false, kept, in);
      }
      return;
    }
    TaylorTerm term{offset(n), -1, 0, 0, factor};
    if (!kept[n] && node.op == TaylorOp::multiply)
      term = {offset(node.a), offset(node.b), nodes_[node.a].degree, nodes_[node.b].degree, factor};
    for (int i = in.first_term; i < in.first_term + in.term_count; ++i)
      if (terms_[i].a == term.a && terms_[i].b == term.b) {
        terms_[i].factor += factor;
        return;
      }
    terms_[term_count_++] = term;
    ++in.term_count;
  }

  // orders from..to of one instruction (inlined into the order-by-order
  // loop, where from = to: a call per instruction and order costs as much as
  // the recurrences of the low orders)
  template <class Real>
  [[gnu::always_inline]] inline void run(const TaylorInstruction& in, int from, int to,
                                         const Context<Real>& x) const {
    switch (in.kernel) {
      case TaylorKernel::constant:
        for (int k = from; k <= to; ++k) x.row(in.out)[k] = k == 0 ? Real(in.shift) : Real(0);
        break;
      case TaylorKernel::time:
        for (int k = from; k <= to; ++k)
          x.row(in.out)[k] = k == 0 ? x.t0 : k == 1 ? Real(1) : Real(0);
        break;
      case TaylorKernel::linear:
        if (from == to)
          linear(in, from, x);
        else
          linear_all_orders(in, from, to, x);
        break;
      case TaylorKernel::multiply:
        for (int k = from; k <= to; ++k) multiply(in, k, x);
        break;
      case TaylorKernel::divide:
        for (int k = from; k <= to; ++k) divide(in, k, x);
        break;
      case TaylorKernel::sin_cos:
        if (in.a_degree == 1 && from == 0 && to > 0)
          sin_cos_of_linear(in, to, x);
        else
          for (int k = from; k <= to; ++k) sin_cos(in, k, x);
        break;
      case TaylorKernel::sign:
        for (int k = from; k <= to; ++k) sign(in, k, x);
        break;
    }
  }

  template <class Real>
  void linear(const TaylorInstruction& in, int k, const Context<Real>& x) const {
    const TaylorTerm* term = &terms_[in.first_term];
    Real sum = 0;
    for (int i = 0; i < in.term_count; ++i) {
      const TaylorTerm& t = term[i];
      if (t.b < 0)
        sum += t.factor * x.row(t.a)[k];
      else
        sum += t.factor * product(x.row(t.a), x.row(t.b), t.a_degree, t.b_degree, k);
    }
    x.row(in.out)[k] = k == 0 ? Real(sum + in.shift) : sum;
  }

  // orders from..to of a linear instruction, term by term (the same sums,
  // in the same order, as linear() order by order; the loops over the
  // orders are contiguous)
  template <class Real>
  void linear_all_orders(const TaylorInstruction& in, int from, int to,
                         const Context<Real>& x) const {
    Real* out = x.row(in.out);
    for (int k = from; k <= to; ++k) out[k] = 0;
    for (int i = in.first_term; i < in.first_term + in.term_count; ++i) {
      const TaylorTerm& t = terms_[i];
      const Real* a = x.row(t.a);
      if (t.b < 0) {
        for (int k = from; k <= to; ++k) out[k] += t.factor * a[k];
      } else {
        const Real* b = x.row(t.b);
        for (int k = from; k <= to; ++k)
          out[k] += t.factor * product(a, b, t.a_degree, t.b_degree, k);
      }
    }
    if (from == 0) out[0] += in.shift;
  }

  template <class Real>
  static void multiply(const TaylorInstruction& in, int k, const Context<Real>& x) {
    x.row(in.out)[k] = product(x.row(in.a), x.row(in.b), in.a_degree, in.b_degree, k);
  }

  // coefficient k of a · b (degrees da, db): the products of coefficients
  // older than k first, the newest (a_0 b_k and a_k b_0, the ones the
  // order-by-order phase has just computed) last: the older part does not
  // wait for them
  template <class Real>
  static Real product(const Real* a, const Real* b, int da, int db, int k) {
    if (k == 0) return a[0] * b[0];
    Real sum = 0;
    for (int j = std::max(1, k - db); j <= std::min(k - 1, da); ++j) sum += a[j] * b[k - j];
    if (k <= db) sum += a[0] * b[k];
    if (k <= da) sum += a[k] * b[0];
    return sum;
  }

  // q = a / b: b0 q_k = a_k − Σ_{j=1..k} b_j q_{k−j}
  template <class Real>
  static void divide(const TaylorInstruction& in, int k, const Context<Real>& x) {
    const Real* b = x.row(in.b);
    Real* out = x.row(in.out);
    Real sum = x.row(in.a)[k];
    for (int j = 1; j <= std::min(k, in.b_degree); ++j) sum -= b[j] * out[k - j];
    out[k] = sum / b[0];
  }

  // s' = c a', c' = −s a': k s_k = Σ j a_j c_{k−j}, k c_k = −Σ j a_j s_{k−j}.
  // Where a is a state component, j a_j = f_{j−1}, its derivative's
  // coefficient (in.rate): read, not computed, which takes two
  // multiplications off the order-by-order chain (the newest term, j = k,
  // needs f_{k−1}, known one order earlier than a_k).
  template <class Real>
  static void sin_cos(const TaylorInstruction& in, int k, const Context<Real>& x) {
    const Real* a = x.row(in.a);
    Real* s = x.row(in.out);
    Real* c = x.row(in.b);
    if (k == 0) {
      sin_and_cos(a[0], s[0], c[0]);
      return;
    }
    Real s_sum = 0, c_sum = 0;
    if (in.rate >= 0) {
      // the two newest terms last: j = 1 (c_{k−1}, s_{k−1}: the previous
      // order's) and j = k (f_{k−1})
      const Real* f = x.row(in.rate);  // j a_j = f_{j−1}
      for (int j = 2; j < k; ++j) {
        s_sum += f[j - 1] * c[k - j];
        c_sum += f[j - 1] * s[k - j];
      }
      if (k > 1) {
        s_sum += f[k - 1] * c[0];
        c_sum += f[k - 1] * s[0];
      }
      s_sum += f[0] * c[k - 1];
      c_sum += f[0] * s[k - 1];
    } else {
      Real* ja = x.row(in.scratch);  // j · a_j
      ja[k] = k * a[k];
      for (int j = 1; j <= std::min(k, in.a_degree); ++j) {
        s_sum += ja[j] * c[k - j];
        c_sum += ja[j] * s[k - j];
      }
    }
    s[k] = s_sum * reciprocal<Real>(k);
    c[k] = -c_sum * reciprocal<Real>(k);
  }

  // orders 0..to of sin and cos of a0 + a1 h (ωt): the recurrence above
  // with its one term, k s_k = a1 c_{k−1}, k c_k = −a1 s_{k−1} (the same
  // operations in the same order, without the loop and the row of j a_j)
  template <class Real>
  static void sin_cos_of_linear(const TaylorInstruction& in, int to, const Context<Real>& x) {
    const Real* a = x.row(in.a);
    Real* s = x.row(in.out);
    Real* c = x.row(in.b);
    sin_and_cos(a[0], s[0], c[0]);
    const Real a1 = a[1];
    for (int k = 1; k <= to; ++k) {
      s[k] = (a1 * c[k - 1]) * reciprocal<Real>(k);
      c[k] = -(a1 * s[k - 1]) * reciprocal<Real>(k);
    }
  }

  // sin v and cos v in one call where the library has it (glibc's sincos
  // for double: the two share their argument reduction)
  template <class Real>
  static void sin_and_cos(const Real& v, Real& s, Real& c) {
    using std::cos;
    using std::sin;
#if defined(__GLIBC__)
    if constexpr (std::is_same_v<Real, double>) {
      ::sincos(v, &s, &c);
      return;
    }
#endif
    s = sin(v);
    c = cos(v);
  }

  template <class Real>
  static void sign(const TaylorInstruction& in, int k, const Context<Real>& x) {
    const Real* a = x.row(in.a);
    Real* out = x.row(in.out);
    if (k > 0)
      out[k] = 0;
    else
      out[0] = x.signs_from_slope && near_zero(a) ? sign_of(a[1]) : sign_of(a[0]);
  }

  // 1 / k (1 <= k <= max_order): a multiplication instead of a division on
  // the order-by-order chain (x_{k+1} = f_k / (k + 1), s_k = Σ / k) in
  // double, where a division's latency is several multiplications'; exact
  // division in the extended-precision types, whose 1/k the table's doubles
  // would round
  template <class Real>
  static Real reciprocal(int k) {
    if constexpr (std::is_same_v<Real, double>) {
      static constexpr auto table = [] {
        std::array<double, max_order + 2> r{};
        for (int j = 1; j <= max_order + 1; ++j) r[j] = 1.0 / j;
        return r;
      }();
      return table[k];
    } else {
      return Real(1) / k;
    }
  }

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
  // the compiled tape: phases 0 (functions of t alone), 1 (state to
  // derivatives, order by order), 2 (the rest) end at phase_end_[0],
  // phase_end_[1], program_count_
  std::array<TaylorInstruction, max_nodes> program_{};
  int program_count_ = 0;
  std::array<int, 2> phase_end_{};
  std::array<int, max_dimension> derivative_offset_{};  // where each f_i's row starts
  // the terms of the linear instructions: each is one operand of a recorded
  // sum or scaling, so there are at most two per node
  std::array<TaylorTerm, 2 * max_nodes> terms_{};
  int term_count_ = 0;
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
