// The Taylor series of several trajectories in one pass over SIMD lanes.
//
// A series' evaluation (integrate/taylor_series.hpp) runs the right-hand side
// once per order, and every order performs the same operations: only the
// coefficients change. So order 0 is run once per trajectory with
// TapeVariable, a number that computes the coefficient 0 of each operation
// exactly as TaylorVariable<double> does and records the operation (its kind,
// the rows of its operands and result, their degrees, a scaling constant) on
// the trajectory's SeriesTape. Trajectories whose tapes record the same
// operations (the same system in the same mode, or systems of one type that
// differ only in their parameters' values) then have their orders 1..p
// computed together by replay_series_tapes, over LaneNumber: one lane per
// trajectory, the recurrences of each operation run from the tape with each
// lane's own constants. Only the arithmetic is per lane: the tape's walk, the
// rows and the loop bounds are paid once for the pass.
//
// Each lane's coefficients are those TaylorSeries<double> computes for that
// trajectory alone, to the last bit: the same IEEE operations in the same
// order (no FMA: the build is ISO C++20, -ffp-contract=off).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>

#include <impactlab/integrate/lane_number.hpp>
#include <impactlab/integrate/series_lane.hpp>
#include <impactlab/integrate/taylor_series.hpp>

namespace impactlab {

// the kinds of operation a tape holds (TaylorVariable's arithmetic, after its
// constant folding)
enum class TapeOperation : std::uint8_t {
  add,                     // a + b
  subtract,                // a − b
  negate,                  // −a
  scale,                   // c · a, c a constant of the lane
  shift,                   // a + c: the constant enters at order 0 only
  subtract_from_constant,  // c − b: likewise
  multiply,                // a · b
  divide,                  // a / b (a may be a constant: zero beyond order 0)
  sin_cos,                 // sin a and cos a, two rows (three: j a_j)
  sign,                    // sign a: constant over the step
  exp,                     // exp a, two rows (the second: j a_j)
  log,                     // log a
  sqrt,                    // √a
  power,                   // a^c, c a constant of the lane
};

// how sin_cos's recurrence runs, by its argument (TaylorVariable's sin_cos)
enum class SineRecurrence : std::uint8_t {
  constant_argument,  // degree 0
  linear_argument,    // degree 1 (ωt)
  state_argument,     // a state component: j a_j read from its derivative's row
  general_argument,   // j a_j kept in a row of its own
};

// One recorded operation: 20 bytes, no padding, so that two tapes compare
// by their bytes.
struct TapeEntry {
  TapeOperation operation = TapeOperation::add;
  SineRecurrence recurrence = SineRecurrence::constant_argument;
  std::int16_t result = -1;  // the result's row (sin_cos: the sine's; the cosine's next, j a_j's after)
  std::int16_t a = -1;       // the operands' rows; −1: a constant
  std::int16_t b = -1;
  std::int16_t rate = -1;    // sin_cos of a state component: the row of its derivative
  std::int16_t padding = 0;  // written, so that the bytes compare
  std::int32_t degree_a = 0;  // the operands' degrees (TaylorVariable::degree)
  std::int32_t degree_b = 0;
};
static_assert(sizeof(TapeEntry) == 20 && std::is_trivially_copyable_v<TapeEntry>);

// One trajectory's order-0 pass: its operations, and every row's coefficient 0.
class SeriesTape {
 public:
  static constexpr int stride = TaylorEvaluation<double>::stride;
  static constexpr int max_rows = TaylorEvaluation<double>::max_rows;
  static constexpr int max_signs = TaylorEvaluation<double>::max_signs;
  static constexpr int max_entries = max_rows;
  static constexpr int max_state = 48;
  static constexpr int max_outputs = 8;
  static constexpr int unbounded = TaylorVariable<double>::unbounded;

  // a new recording for `dimension` state components: rows 0..N−1 the
  // state, N..2N−1 its derivatives, 2N the time (TaylorSeries' layout)
  void start(int dimension) {
    dimension_ = dimension;
    rows_taken_ = 2 * dimension + 1;
    entry_count_ = 0;
    output_count_ = 0;
    sign_count_ = 0;
  }

  int take_row() {
    if (rows_taken_ == max_rows) throw_too_many_operations();
    return rows_taken_++;
  }
  TapeEntry& add_entry(TapeOperation operation, double constant = 0.0) {
    if (entry_count_ == max_entries) throw_too_many_operations();
    constants_[entry_count_] = constant;
    TapeEntry& entry = entries_[entry_count_++];
    entry = TapeEntry{};
    entry.operation = operation;
    return entry;
  }
  void set_coefficient0(int row, double value) { coefficient0_[row] = value; }
  void note_sign_argument(int row) {
    if (sign_count_ < max_signs) sign_rows_[sign_count_++] = static_cast<std::int16_t>(row);
  }
  // state component i's derivative: the row it is read from (−1: a constant)
  void set_derivative(int i, int row, double coefficient0) {
    derivative_rows_[i] = static_cast<std::int16_t>(row);
    coefficient0_[dimension_ + i] = coefficient0;
  }
  void add_output(int row, bool constant) {
    output_rows_[output_count_] = static_cast<std::int16_t>(row);
    output_is_constant_[output_count_] = constant;
    ++output_count_;
  }

  // Whether two tapes record the same operations on the same rows (their
  // constants and coefficients may differ): one pass computes both.
  [[nodiscard]] bool same_operations(const SeriesTape& other) const {
    return dimension_ == other.dimension_ && rows_taken_ == other.rows_taken_ &&
           entry_count_ == other.entry_count_ && output_count_ == other.output_count_ &&
           sign_count_ == other.sign_count_ &&
           std::memcmp(entries_.data(), other.entries_.data(), entry_count_ * sizeof(TapeEntry)) == 0 &&
           std::equal(derivative_rows_.begin(), derivative_rows_.begin() + dimension_,
                      other.derivative_rows_.begin()) &&
           std::equal(output_rows_.begin(), output_rows_.begin() + output_count_,
                      other.output_rows_.begin()) &&
           std::equal(output_is_constant_.begin(), output_is_constant_.begin() + output_count_,
                      other.output_is_constant_.begin()) &&
           std::equal(sign_rows_.begin(), sign_rows_.begin() + sign_count_, other.sign_rows_.begin());
  }

  [[nodiscard]] int dimension() const { return dimension_; }
  [[nodiscard]] int rows_taken() const { return rows_taken_; }
  [[nodiscard]] int entry_count() const { return entry_count_; }
  [[nodiscard]] const TapeEntry& entry(int i) const { return entries_[i]; }
  [[nodiscard]] double constant(int i) const { return constants_[i]; }
  [[nodiscard]] double coefficient0(int row) const { return coefficient0_[row]; }
  [[nodiscard]] int derivative_row(int i) const { return derivative_rows_[i]; }
  [[nodiscard]] int output_count() const { return output_count_; }
  [[nodiscard]] int output_row(int j) const { return output_rows_[j]; }
  [[nodiscard]] bool output_is_constant(int j) const { return output_is_constant_[j]; }
  [[nodiscard]] int sign_count() const { return sign_count_; }
  [[nodiscard]] int sign_row(int i) const { return sign_rows_[i]; }

 private:
  int dimension_ = 0;
  int rows_taken_ = 0;
  int entry_count_ = 0;
  int output_count_ = 0;
  int sign_count_ = 0;
  std::array<TapeEntry, max_entries> entries_{};
  std::array<double, max_entries> constants_{};  // scale's factor, power's exponent, per entry
  std::array<double, max_rows> coefficient0_{};
  std::array<std::int16_t, max_state> derivative_rows_{};
  std::array<std::int16_t, max_outputs> output_rows_{};
  std::array<bool, max_outputs> output_is_constant_{};
  std::array<std::int16_t, max_signs> sign_rows_{};
};

// A number of the order-0 pass: a constant, or a series whose coefficient 0 is
// `value` in row `row` of the tape. Its arithmetic is TaylorVariable's at
// order 0, operation for operation (the same constant folding, the same
// rows taken in the same order, the same degrees), each recorded.
class TapeVariable {
 public:
  static constexpr int unbounded = SeriesTape::unbounded;

  TapeVariable() = default;
  TapeVariable(double constant) : value_(constant) {}  // NOLINT: constants mix in freely
  TapeVariable(SeriesTape* tape, int row, double value, int degree, int rate = -1)
      : tape_(tape), value_(value), row_(row), rate_(rate), degree_(degree) {}

  [[nodiscard]] bool is_constant() const { return tape_ == nullptr; }
  [[nodiscard]] double constant() const { return value_; }
  [[nodiscard]] double value() const { return value_; }
  [[nodiscard]] SeriesTape* tape() const { return tape_; }
  [[nodiscard]] int row() const { return row_; }
  [[nodiscard]] int rate() const { return rate_; }
  [[nodiscard]] int degree() const { return degree_; }

  // an operation's result: a new row holding its coefficient 0
  static TapeVariable result(TapeEntry& entry, SeriesTape* tape, double value, int degree) {
    const int row = tape->take_row();
    entry.result = static_cast<std::int16_t>(row);
    tape->set_coefficient0(row, value);
    return {tape, row, value, std::min(degree, unbounded)};
  }

 private:
  SeriesTape* tape_ = nullptr;
  double value_ = 0.0;
  int row_ = -1;
  int rate_ = -1;
  int degree_ = 0;
};

namespace detail {

inline TapeEntry& tape_entry(TapeOperation operation, const TapeVariable& a,
                             const TapeVariable& b = TapeVariable(), double constant = 0.0) {
  SeriesTape* tape = a.is_constant() ? b.tape() : a.tape();
  TapeEntry& entry = tape->add_entry(operation, constant);
  entry.a = static_cast<std::int16_t>(a.row());
  entry.b = static_cast<std::int16_t>(b.row());
  entry.degree_a = a.degree();
  entry.degree_b = b.degree();
  return entry;
}

inline TapeVariable tape_scaled(const TapeVariable& a, double c) {
  return TapeVariable::result(tape_entry(TapeOperation::scale, a, TapeVariable(), c), a.tape(),
                              c * a.value(), a.degree());
}

inline TapeVariable tape_shifted(const TapeVariable& a, double c) {
  return TapeVariable::result(tape_entry(TapeOperation::shift, a), a.tape(), a.value() + c,
                              a.degree());
}

inline std::array<TapeVariable, 2> tape_sin_cos(const TapeVariable& a) {
  SeriesTape* tape = a.tape();
  TapeEntry& entry = tape_entry(TapeOperation::sin_cos, a);
  entry.rate = static_cast<std::int16_t>(a.rate());
  const int s = tape->take_row();
  const int c = tape->take_row();
  if (a.degree() > 1 && a.rate() < 0) tape->take_row();
  entry.result = static_cast<std::int16_t>(s);
  entry.recurrence = a.degree() == 0   ? SineRecurrence::constant_argument
                     : a.degree() == 1 ? SineRecurrence::linear_argument
                     : a.rate() >= 0   ? SineRecurrence::state_argument
                                       : SineRecurrence::general_argument;
  double s0 = 0.0, c0 = 0.0;
  sin_and_cos(a.value(), s0, c0);
  tape->set_coefficient0(s, s0);
  tape->set_coefficient0(c, c0);
  return {TapeVariable(tape, s, s0, TapeVariable::unbounded),
          TapeVariable(tape, c, c0, TapeVariable::unbounded)};
}

}  // namespace detail

inline double start_value(const TapeVariable& v) { return v.value(); }

inline TapeVariable operator+(const TapeVariable& a, const TapeVariable& b) {
  if (a.is_constant() && b.is_constant()) return a.value() + b.value();
  if (b.is_constant()) return detail::tape_shifted(a, b.value());
  if (a.is_constant()) return detail::tape_shifted(b, a.value());
  return TapeVariable::result(detail::tape_entry(TapeOperation::add, a, b), a.tape(),
                              a.value() + b.value(), std::max(a.degree(), b.degree()));
}

inline TapeVariable operator-(const TapeVariable& a) {
  if (a.is_constant()) return -a.value();
  return TapeVariable::result(detail::tape_entry(TapeOperation::negate, a), a.tape(), -a.value(),
                              a.degree());
}

inline TapeVariable operator-(const TapeVariable& a, const TapeVariable& b) {
  if (a.is_constant() && b.is_constant()) return a.value() - b.value();
  if (b.is_constant()) return detail::tape_shifted(a, -b.value());
  if (a.is_constant())
    return TapeVariable::result(detail::tape_entry(TapeOperation::subtract_from_constant, a, b),
                                b.tape(), a.value() - b.value(), b.degree());
  return TapeVariable::result(detail::tape_entry(TapeOperation::subtract, a, b), a.tape(),
                              a.value() - b.value(), std::max(a.degree(), b.degree()));
}

inline TapeVariable operator*(const TapeVariable& a, const TapeVariable& b) {
  if (a.is_constant() && b.is_constant()) return a.value() * b.value();
  if (a.is_constant()) return detail::tape_scaled(b, a.value());
  if (b.is_constant()) return detail::tape_scaled(a, b.value());
  const int degree = std::min(TapeVariable::unbounded, a.degree() + b.degree());
  return TapeVariable::result(detail::tape_entry(TapeOperation::multiply, a, b), a.tape(),
                              a.value() * b.value(), degree);
}

inline TapeVariable operator/(const TapeVariable& a, const TapeVariable& b) {
  if (b.is_constant()) return a * TapeVariable(1.0 / b.value());
  TapeEntry& entry = detail::tape_entry(TapeOperation::divide, a, b);
  const int degree = b.degree() == 0 ? a.degree() : TapeVariable::unbounded;
  return TapeVariable::result(entry, b.tape(), a.value() / b.value(), degree);
}

inline TapeVariable operator+(const TapeVariable& a, double b) { return a + TapeVariable(b); }
inline TapeVariable operator+(double a, const TapeVariable& b) { return TapeVariable(a) + b; }
inline TapeVariable operator-(const TapeVariable& a, double b) { return a - TapeVariable(b); }
inline TapeVariable operator-(double a, const TapeVariable& b) { return TapeVariable(a) - b; }
inline TapeVariable operator*(const TapeVariable& a, double b) { return a * TapeVariable(b); }
inline TapeVariable operator*(double a, const TapeVariable& b) { return TapeVariable(a) * b; }
inline TapeVariable operator/(const TapeVariable& a, double b) { return a / TapeVariable(b); }
inline TapeVariable operator/(double a, const TapeVariable& b) { return TapeVariable(a) / b; }

template <class Other>
TapeVariable& operator+=(TapeVariable& a, const Other& b) { return a = a + b; }
template <class Other>
TapeVariable& operator-=(TapeVariable& a, const Other& b) { return a = a - b; }
template <class Other>
TapeVariable& operator*=(TapeVariable& a, const Other& b) { return a = a * b; }
template <class Other>
TapeVariable& operator/=(TapeVariable& a, const Other& b) { return a = a / b; }

inline TapeVariable sin(const TapeVariable& a) {
  if (a.is_constant()) return detail::constant_sin_cos(a.value())[0];
  return detail::tape_sin_cos(a)[0];
}
inline TapeVariable cos(const TapeVariable& a) {
  if (a.is_constant()) return detail::constant_sin_cos(a.value())[1];
  return detail::tape_sin_cos(a)[1];
}
inline SineAndCosine<TapeVariable> sin_and_cos_of(const TapeVariable& a) {
  if (a.is_constant())
    return {detail::constant_sin_cos(a.value())[0], detail::constant_sin_cos(a.value())[1]};
  const std::array<TapeVariable, 2> pair = detail::tape_sin_cos(a);
  return {pair[0], pair[1]};
}
inline TapeVariable sin_angle(const TapeVariable& a) { return sin(a); }
inline TapeVariable cos_phase(const TapeVariable& a) { return cos(a); }
inline TapeVariable sin_phase(const TapeVariable& a) { return sin(a); }

// exp a, log a, √a and a^α: TaylorVariable's at order 0, recorded
inline TapeVariable exp(const TapeVariable& a) {
  using std::exp;
  if (a.is_constant()) return exp(a.value());
  SeriesTape* tape = a.tape();
  TapeEntry& entry = detail::tape_entry(TapeOperation::exp, a);
  const TapeVariable e = TapeVariable::result(entry, tape, exp(a.value()),
                                              detail::function_degree(a.degree()));
  tape->take_row();  // j a_j
  return e;
}
inline TapeVariable log(const TapeVariable& a) {
  using std::log;
  if (a.is_constant()) return log(a.value());
  return TapeVariable::result(detail::tape_entry(TapeOperation::log, a), a.tape(), log(a.value()),
                              detail::function_degree(a.degree()));
}
inline TapeVariable sqrt(const TapeVariable& a) {
  using std::sqrt;
  if (a.is_constant()) return sqrt(a.value());
  return TapeVariable::result(detail::tape_entry(TapeOperation::sqrt, a), a.tape(), sqrt(a.value()),
                              detail::function_degree(a.degree()));
}
inline TapeVariable pow(const TapeVariable& a, double alpha) {
  using std::pow;
  if (a.is_constant()) return pow(a.value(), alpha);
  return TapeVariable::result(detail::tape_entry(TapeOperation::power, a, TapeVariable(), alpha),
                              a.tape(), pow(a.value(), alpha),
                              detail::function_degree(a.degree()));
}

// TaylorVariable's sign at order 0 without the slope (a batch's evaluation:
// a lane whose signs need their slope evaluates again alone)
inline TapeVariable sign(const TapeVariable& a) {
  if (a.is_constant()) return detail::sign_of(a.value());
  a.tape()->note_sign_argument(a.row());
  return TapeVariable::result(detail::tape_entry(TapeOperation::sign, a), a.tape(),
                              detail::sign_of(a.value()), 0);
}
inline TapeVariable fabs(const TapeVariable& a) { return sign(a) * a; }

namespace detail {

template <std::size_t N, class Rhs>
void record_series_tape_pass(SeriesTape& tape, const double* x0, double t0, const Rhs& rhs) {
  static_assert(N <= SeriesTape::max_state);
  tape.start(static_cast<int>(N));
  std::array<TapeVariable, N> x, dxdt;
  std::array<TapeVariable, SeriesTape::max_outputs> outputs;
  for (std::size_t i = 0; i < N; ++i) {
    tape.set_coefficient0(static_cast<int>(i), x0[i]);
    x[i] = TapeVariable(&tape, static_cast<int>(i), x0[i], TapeVariable::unbounded,
                        static_cast<int>(N + i));
  }
  tape.set_coefficient0(static_cast<int>(2 * N), t0);
  const TapeVariable t(&tape, static_cast<int>(2 * N), t0, 1);
  const int count = rhs(x, t, dxdt, outputs);
  for (std::size_t i = 0; i < N; ++i)
    tape.set_derivative(static_cast<int>(i), dxdt[i].row(), dxdt[i].value());
  for (int j = 0; j < count; ++j) {
    // an output that is a constant gets a row of its own
    const TapeVariable& out = outputs[j];
    if (out.is_constant()) {
      const int row = tape.take_row();
      tape.set_coefficient0(row, out.value());
      tape.add_output(row, true);
    } else {
      tape.add_output(out.row(), false);
    }
  }
}

template <std::size_t N, class Rhs>
[[gnu::flatten]] void record_series_tape_flattened(SeriesTape& tape, const double* x0, double t0,
                                                   const Rhs& rhs) {
  record_series_tape_pass<N>(tape, x0, t0, rhs);
}

// The most states whose recording has every operation inlined into it: the
// larger systems (the rigid pendulum's variational equations, 14 states)
// made the translation unit of their flows twice as long to compile with it;
// their recordings call the operations instead.
inline constexpr std::size_t flattened_tape_states = 8;

}  // namespace detail

// Records the order-0 pass of `rhs` (TaylorSeries' contract: rhs(x, t, dxdt,
// outputs) returns how many outputs it set) at (t0, x0) on `tape`.
template <std::size_t N, class Rhs>
void record_series_tape(SeriesTape& tape, const double* x0, double t0, const Rhs& rhs) {
  if constexpr (N <= detail::flattened_tape_states)
    detail::record_series_tape_flattened<N>(tape, x0, t0, rhs);
  else
    detail::record_series_tape_pass<N>(tape, x0, t0, rhs);
}

// the most trajectories of one pass: two quads of lanes, so that two
// independent chains of each recurrence run side by side; a pass of at most
// four runs one quad (docs/performance.md, "Many trajectories at once")
inline constexpr int tape_lane_width = 8;

// The coefficients of a pass: rows × orders, one lane per trajectory, as
// LaneNumber<4 · quads> (the pass's width).
class SeriesLaneRows {
 public:
  static constexpr int size = SeriesTape::max_rows * SeriesTape::stride;

  // the rows of a pass of `quads` quads, to be written
  template <int Quads>
  LaneNumber<4 * Quads>* start_pass() {
    static_assert(Quads >= 1 && 4 * Quads <= tape_lane_width);
    quads_ = Quads;
    return std::launder(reinterpret_cast<LaneNumber<4 * Quads>*>(storage_));
  }
  [[nodiscard]] double coefficient(int row, int k, int lane) const {
    const int index = row * SeriesTape::stride + k;
    if (quads_ == 1) return rows<1>()[index].lane(lane);
    return rows<2>()[index].lane(lane);
  }
  // lane `lane`'s coefficient 0 of `row`, where its coefficient k lies
  // k · lane_stride() doubles further on: for a stepper that reads its
  // coefficients where the pass wrote them (a quad's lanes are its
  // elements, each quad right after the one before)
  [[nodiscard]] const double* lane_coefficients(int row, int lane) const {
    return reinterpret_cast<const double*>(storage_) +
           static_cast<std::ptrdiff_t>(row) * SeriesTape::stride * lane_stride() + lane;
  }
  [[nodiscard]] int lane_stride() const { return 4 * quads_; }
  // lane `lane`'s coefficients 0..order of `row`, into `to`
  void copy_lane(int row, int order, int lane, double* to) const {
    const int index = row * SeriesTape::stride;
    if (quads_ == 1) {
      const LaneNumber<4>* from = rows<1>() + index;
      for (int k = 0; k <= order; ++k) to[k] = from[k].lane(lane);
    } else {
      const LaneNumber<8>* from = rows<2>() + index;
      for (int k = 0; k <= order; ++k) to[k] = from[k].lane(lane);
    }
  }

 private:
  static_assert(tape_lane_width == 8, "coefficient() reads passes of one or two quads");
  template <int Quads>
  [[nodiscard]] const LaneNumber<4 * Quads>* rows() const {
    return std::launder(reinterpret_cast<const LaneNumber<4 * Quads>*>(storage_));
  }
  int quads_ = 0;
  // room for the widest pass; each pass's numbers begin their lifetime in
  // it (an array of bytes gives them storage)
  alignas(LaneNumber<tape_lane_width>) std::byte storage_[size * sizeof(LaneNumber<tape_lane_width>)];
};

// The rows of the passes of one round of a batch (simulate/series_batch.hpp),
// each pass's its own: a stepper reads its coefficients where its pass wrote
// them, until its next request, when the batch starts the next round.
// Made once per batch; nothing is allocated while the lanes step.
class SeriesLaneRowsPool {
 public:
  // a pass has two lanes at least
  static constexpr int capacity = max_series_lanes / 2;

  SeriesLaneRowsPool() : rows_(std::make_unique_for_overwrite<SeriesLaneRows[]>(capacity)) {}

  // rows for the next pass of this round
  SeriesLaneRows& take() {
    if (taken_ == capacity) throw std::logic_error("series: more passes in a round than lanes allow");
    return rows_[taken_++];
  }
  // every lane has posted its next request: the rows of the last round are
  // no longer read
  void start_round() { taken_ = 0; }

 private:
  std::unique_ptr<SeriesLaneRows[]> rows_;
  int taken_ = 0;
};

// The coefficients 0..order of every row of `count` (1..tape_lane_width)
// tapes that record the same operations (SeriesTape::same_operations), lane
// i from tapes[i]; spare lanes repeat the first.
void replay_series_tapes(const std::array<const SeriesTape*, tape_lane_width>& tapes, int count,
                         int order, SeriesLaneRows& out);

}  // namespace impactlab
