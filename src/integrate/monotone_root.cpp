// Roots of monotone polynomial pieces refined several lanes at a time.
#include <impactlab/integrate/monotone_root.hpp>

#include <algorithm>
#include <array>
#include <cstring>

#include <impactlab/integrate/lane_number.hpp>
#include <impactlab/integrate/taylor_series.hpp>

namespace impactlab {

namespace {

// up to B problems, lane by lane, their coefficients padded with zeros to
// the largest degree (a leading zero leaves Horner's sums unchanged to the
// bit: 0 · x² + c = c)
template <int B>
struct LaneProblems {
  using Lanes = LaneNumber<B>;
  std::array<Lanes, taylor_max_order + 1> p;
  std::array<Lanes, taylor_max_order + 1> dp;
  std::array<Lanes, taylor_max_order + 1> ddp;
  int degree = 0;
  Lanes lo, hi, f_lo, f_hi, t_scale;
};

template <int B>
void narrow_lanes(const LaneProblems<B>& q, LaneNumber<B>& a, LaneNumber<B>& b) {
  using Lanes = LaneNumber<B>;
  a = q.lo;
  b = q.hi;
  detail::narrow_monotone_bracket<Lanes>(q.p.data(), q.dp.data(), q.ddp.data(), q.degree, a, b,
                                         q.f_lo, q.f_hi, q.t_scale, Lanes(0.0), Lanes(0.5),
                                         Lanes(4 * std::numeric_limits<double>::epsilon()));
}

#if defined(__x86_64__) && defined(__GNUC__)
// the same, compiled for AVX2 (each quad of lanes in one register; no FMA)
template <int B>
[[gnu::target("avx2"), gnu::flatten]] void narrow_lanes_avx2(const LaneProblems<B>& q,
                                                            LaneNumber<B>& a, LaneNumber<B>& b) {
  narrow_lanes(q, a, b);
}
#endif

// problems[0..count) (count ≤ B) into roots[0..count); spare lanes repeat
// the first problem
template <int B>
void refine_in_lanes(const MonotoneRootProblem<double>* const* problems, int count,
                     double* roots) {
  using Lanes = LaneNumber<B>;
  auto problem = [&](int lane) -> const MonotoneRootProblem<double>& {
    return *problems[lane < count ? lane : 0];
  };
  LaneProblems<B> q;
  for (int lane = 0; lane < B; ++lane) q.degree = std::max(q.degree, problem(lane).degree);
  // each number gathered in an array of doubles and copied whole (as a
  // pass over lanes does: integrate/series_tape.cpp)
  auto gather = [&](auto value_of) {
    std::array<double, B> values;
    for (int lane = 0; lane < B; ++lane) values[lane] = value_of(problem(lane));
    Lanes number;
    std::memcpy(&number, values.data(), sizeof number);
    return number;
  };
  using Problem = MonotoneRootProblem<double>;
  // the coefficients lane by lane into the lanes' layout (coefficient j of
  // lane l at j·B + l), then copied whole
  std::array<double, (taylor_max_order + 1) * B> coefficients;
  for (int lane = 0; lane < B; ++lane) {
    const Problem& one = problem(lane);
    for (int j = 0; j <= q.degree; ++j)
      coefficients[j * B + lane] = j <= one.degree ? one.p[j] : 0.0;
  }
  static_assert(sizeof(Lanes) == B * sizeof(double));
  std::memcpy(q.p.data(), coefficients.data(), (q.degree + 1) * sizeof(Lanes));
  // the derivatives as the problems hold them (MonotoneRootProblem), each
  // product the same IEEE multiplication in its lane; zero past a lane's
  // degree, as the padding of p
  for (int j = 0; j < q.degree; ++j) q.dp[j] = q.p[j + 1] * Lanes(static_cast<double>(j + 1));
  for (int j = 0; j + 1 < q.degree; ++j)
    q.ddp[j] = q.dp[j + 1] * Lanes(static_cast<double>(j + 1));
  q.lo = gather([](const Problem& one) { return one.lo; });
  q.hi = gather([](const Problem& one) { return one.hi; });
  q.f_lo = gather([](const Problem& one) { return one.f_lo; });
  q.f_hi = gather([](const Problem& one) { return one.f_hi; });
  q.t_scale = gather([](const Problem& one) { return one.t_scale; });
  Lanes a, b;
#if defined(__x86_64__) && defined(__GNUC__)
  if (lane_passes_available())
    narrow_lanes_avx2(q, a, b);
  else
    narrow_lanes(q, a, b);
#else
  narrow_lanes(q, a, b);
#endif
  for (int lane = 0; lane < count; ++lane)
    roots[lane] = problem(lane).towards_hi ? b.lane(lane) : (a.lane(lane) + b.lane(lane)) * 0.5;
}

}  // namespace

void refine_monotone_roots(const MonotoneRootProblem<double>* const* problems, int count,
                           double* roots) {
  for (int first = 0; first < count; first += 8) {
    const int n = std::min(8, count - first);
    if (n <= 4)
      refine_in_lanes<4>(problems + first, n, roots + first);
    else
      refine_in_lanes<8>(problems + first, n, roots + first);
  }
}

void evaluate_root_requests(SeriesRequest* const* requests, int count) {
  std::array<const MonotoneRootProblem<double>*, max_series_lanes> problems{};
  std::array<double, max_series_lanes> roots{};
  for (int i = 0; i < count; ++i) problems[i] = &static_cast<RootRequest*>(requests[i])->problem;
  refine_monotone_roots(problems.data(), count, roots.data());
  for (int i = 0; i < count; ++i) {
    auto* request = static_cast<RootRequest*>(requests[i]);
    request->root = roots[i];
  }
}

}  // namespace impactlab
