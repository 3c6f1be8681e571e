#include <impactlab/integrate/series_tape.hpp>

#include <algorithm>
#include <cstring>

namespace impactlab {
namespace {

constexpr int stride = SeriesTape::stride;

template <class Lanes>
using LaneConstants = std::array<Lanes, SeriesTape::max_entries>;

// An entry of the tape with its rows resolved to addresses in the pass's
// storage, and its constant in lanes: what each order reads, worked out
// once for the pass.
template <class Lanes>
struct ResolvedEntry {
  TapeOperation operation;
  SineRecurrence recurrence;
  int degree_a;
  int degree_b;
  Lanes* result;
  const Lanes* x;  // operand a's row (sin_cos: its argument's), or nullptr: a constant
  const Lanes* y;  // operand b's row, or nullptr
  const Lanes* f;  // sin_cos of a state component: its derivative's row
  Lanes constant;  // scale's factor, power's exponent, lane by lane
};

// Orders 1..order of every operation of the tape, each recurrence written as
// TaylorVariable's (integrate/taylor_series.hpp) for k >= 1, the operands'
// coefficient k read from their rows. A sign, and sin and cos of a constant,
// are zero beyond order 0: written once, not walked at every order.
template <class Lanes>
void replay_orders(const SeriesTape& tape, const LaneConstants<Lanes>& constants, int order,
                   Lanes* rows) {
  auto row = [rows](int r) { return rows + r * stride; };
  std::array<ResolvedEntry<Lanes>, SeriesTape::max_entries> resolved;
  int walked = 0;
  for (int e = 0; e < tape.entry_count(); ++e) {
    const TapeEntry& entry = tape.entry(e);
    Lanes* result = row(entry.result);
    const bool constant_sine = entry.operation == TapeOperation::sin_cos &&
                               entry.recurrence == SineRecurrence::constant_argument;
    if (entry.operation == TapeOperation::sign || constant_sine) {
      for (int k = 1; k <= order; ++k) result[k] = 0.0;
      if (constant_sine)
        for (int k = 1; k <= order; ++k) result[stride + k] = 0.0;
      continue;
    }
    resolved[walked++] = {entry.operation,
                          entry.recurrence,
                          entry.degree_a,
                          entry.degree_b,
                          result,
                          entry.a >= 0 ? row(entry.a) : nullptr,
                          entry.b >= 0 ? row(entry.b) : nullptr,
                          entry.rate >= 0 ? row(entry.rate) : nullptr,
                          constants[e]};
  }
  const int n = tape.dimension();
  Lanes* time = row(2 * n);
  for (int k = 1; k <= order; ++k) {
    time[k] = k == 1 ? Lanes(1.0) : Lanes(0.0);
    for (int e = 0; e < walked; ++e) {
      const ResolvedEntry<Lanes>& entry = resolved[e];
      Lanes* result = entry.result;
      const Lanes* x = entry.x;
      const Lanes* y = entry.y;
      switch (entry.operation) {
        case TapeOperation::add:
          result[k] = x[k] + y[k];
          break;
        case TapeOperation::subtract:
          result[k] = x[k] - y[k];
          break;
        case TapeOperation::negate:
          result[k] = -x[k];
          break;
        case TapeOperation::scale:
          result[k] = entry.constant * x[k];
          break;
        case TapeOperation::shift:
          result[k] = x[k];
          break;
        case TapeOperation::subtract_from_constant:
          result[k] = -y[k];
          break;
        case TapeOperation::multiply:
          result[k] = detail::product_coefficient(x, y, x[k], y[k], k, entry.degree_a, entry.degree_b);
          break;
        case TapeOperation::divide:
          result[k] = detail::quotient_coefficient(x != nullptr ? x[k] : Lanes(0.0), y, y[k],
                                                   result, k, entry.degree_b);
          break;
        case TapeOperation::sin_cos: {
          Lanes* s = result;
          Lanes* c = result + stride;
          Lanes sk, ck;
          if (entry.recurrence == SineRecurrence::linear_argument) {
            detail::sine_of_linear(x[1], s, c, k, sk, ck);
          } else if (entry.recurrence == SineRecurrence::state_argument) {
            detail::sine_of_state(entry.f, s, c, k, sk, ck);
          } else {
            Lanes* ja = result + 2 * stride;
            ja[k] = Lanes(static_cast<double>(k)) * x[k];
            detail::sine_of_series(ja, entry.degree_a, s, c, k, sk, ck);
          }
          s[k] = sk;
          c[k] = ck;
          break;
        }
        case TapeOperation::exp: {
          Lanes* ja = result + stride;
          ja[k] = Lanes(static_cast<double>(k)) * x[k];
          result[k] = detail::exp_coefficient(ja, entry.degree_a, result, k);
          break;
        }
        case TapeOperation::log:
          result[k] = detail::log_coefficient(x, entry.degree_a, result, k);
          break;
        case TapeOperation::sqrt:
          result[k] = detail::sqrt_coefficient(x[k], result, k);
          break;
        case TapeOperation::power:
          result[k] = detail::power_coefficient(entry.constant, x, entry.degree_a, result, k);
          break;
        case TapeOperation::sign:
          break;
      }
    }
    for (int i = 0; i < n; ++i) {
      const int from = tape.derivative_row(i);
      const Lanes f = from >= 0 ? row(from)[k] : Lanes(0.0);
      row(n + i)[k] = f;
      if (k < order) row(i)[k + 1] = f * taylor_reciprocal<Lanes>(k + 1);
    }
    for (int j = 0; j < tape.output_count(); ++j)
      if (tape.output_is_constant(j)) row(tape.output_row(j))[k] = 0.0;
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
// the same, compiled for AVX2 (each quad of lanes in one register; not FMA:
// the products and sums stay separate IEEE operations)
template <class Lanes>
[[gnu::target("avx2"), gnu::flatten]] void replay_avx2(const SeriesTape& tape,
                                                      const LaneConstants<Lanes>& constants,
                                                      int order, Lanes* rows) {
  replay_orders(tape, constants, order, rows);
}
#endif

// The pass over `Quads` quads of lanes: order 0 (and the state's
// coefficient 1) as each lane's recording left it, then orders 1..order.
// Spare lanes repeat the first.
template <int Quads>
void replay_pass(const std::array<const SeriesTape*, tape_lane_width>& tapes, int count, int order,
                 SeriesLaneRows& out) {
  using Lanes = LaneNumber<4 * Quads>;
  const SeriesTape& first = *tapes[0];
  const int n = first.dimension();
  Lanes* rows = out.start_pass<Quads>();
  auto lane_tape = [&](int lane) -> const SeriesTape& { return *tapes[lane < count ? lane : 0]; };
  // each number gathered in an array of doubles and copied whole: inserted
  // lane by lane into its vectors, setting up a pass took twice as long
  // (4 % of a basins grid's time against 2 %)
  auto gather = [&](auto value_of) {
    std::array<double, Lanes::width> values;
    for (int lane = 0; lane < Lanes::width; ++lane) values[lane] = value_of(lane_tape(lane));
    Lanes number;
    std::memcpy(&number, values.data(), sizeof number);
    return number;
  };
  for (int r = 0; r < first.rows_taken(); ++r)
    rows[r * stride] = gather([r](const SeriesTape& tape) { return tape.coefficient0(r); });
  for (int i = 0; i < n; ++i)
    rows[i * stride + 1] = gather([n, i](const SeriesTape& tape) {
      return tape.coefficient0(n + i) * taylor_reciprocal<double>(1);
    });
  LaneConstants<Lanes> constants;
  for (int e = 0; e < first.entry_count(); ++e)
    constants[e] = gather([e](const SeriesTape& tape) { return tape.constant(e); });
#if defined(__x86_64__) && defined(__GNUC__)
  if (lane_passes_available()) {
    replay_avx2(first, constants, order, rows);
    return;
  }
#endif
  replay_orders(first, constants, order, rows);
}

}  // namespace

void replay_series_tapes(const std::array<const SeriesTape*, tape_lane_width>& tapes, int count,
                         int order, SeriesLaneRows& out) {
  if (count <= 4)
    replay_pass<1>(tapes, count, order, out);
  else
    replay_pass<2>(tapes, count, order, out);
}

}  // namespace impactlab
