#include <impactlab/analysis/chatter_onset.hpp>

#include <algorithm>
#include <cstdint>
#include <utility>

#include <boost/math/tools/toms748_solve.hpp>

namespace impactlab {

std::optional<SelfSimilarChatter> self_similar_chatter(double restitution) {
  const double r = restitution;
  if (!(r > 0.0 && r < 1.0)) return std::nullopt;
  // (3 − z)(1 − z)² − r (3 − 2z): 3(1 − r) > 0 at z = 0, −r < 0 at z = 1
  const auto fixed_point = [r](double z) { return (3.0 - z) * (1.0 - z) * (1.0 - z) - r * (3.0 - 2.0 * z); };
  std::uintmax_t iterations = 200;
  const auto bracket = boost::math::tools::toms748_solve(
      fixed_point, 0.0, 1.0, 3.0 * (1.0 - r), -r, boost::math::tools::eps_tolerance<double>(53),
      iterations);
  SelfSimilarChatter chatter;
  const double z = 0.5 * (bracket.first + bracket.second);
  chatter.hop_fraction = z;
  chatter.remaining_ratio = 1.0 - z;
  chatter.scaled_speed = (3.0 * z - z * z) / 6.0;
  chatter.multiplier = (3.0 - z) * (3.0 - z) / ((1.0 - z) * (3.0 - 2.0 * z) * (3.0 - 2.0 * z));
  chatter.index = std::log(1e4) / std::log(chatter.multiplier);
  return chatter;
}

namespace {

// The first zero of the push after t (where it is positive), up to horizon:
// doubling steps from `step`, then TOMS 748; NaN where none is found.
double push_zero_after(double t, double step, double horizon,
                       const std::function<double(double)>& push_at_rest) {
  double low = t, push_low = push_at_rest(t);
  if (!(push_low > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  double high = low, push_high = push_low;
  for (int doubling = 0; doubling < 200 && push_high > 0.0; ++doubling) {
    low = high;
    push_low = push_high;
    high = low + step;
    if (high > horizon) return std::numeric_limits<double>::quiet_NaN();
    push_high = push_at_rest(high);
    if (!std::isfinite(push_high)) return std::numeric_limits<double>::quiet_NaN();
    step *= 2.0;
  }
  if (push_high > 0.0) return std::numeric_limits<double>::quiet_NaN();
  if (push_high == 0.0) return high;
  std::uintmax_t iterations = 200;
  const auto bracket = boost::math::tools::toms748_solve(
      push_at_rest, low, high, push_low, push_high, boost::math::tools::eps_tolerance<double>(53),
      iterations);
  return 0.5 * (bracket.first + bracket.second);
}

}  // namespace

ChatterMargin chatter_run_margin(std::span<const ChatterImpact> run, bool accumulated,
                                 const std::function<double(double)>& push_at_rest,
                                 double horizon) {
  ChatterMargin result;
  std::size_t first = run.size();
  std::size_t in_sticking_region = 0;
  for (std::size_t k = 0; k < run.size(); ++k) {
    if (!(push_at_rest(run[k].t) > 0.0)) continue;
    if (first == run.size()) first = k;
    ++in_sticking_region;
  }
  if (in_sticking_region < 2) return result;
  result.side = accumulated ? 1 : -1;
  // the restitution of the run's second impact (a Newton impact law: the
  // same at every impact)
  const auto self_similar = self_similar_chatter(run[1].restitution);
  if (!self_similar) return result;
  result.index = self_similar->index;
  const double step = std::max(run[first + 1].t - run[first].t, 1e-12 * (1.0 + std::fabs(run[first].t)));
  const double release = push_zero_after(run[first].t, step, horizon, push_at_rest);
  if (!std::isfinite(release)) return result;
  std::size_t before = 0;  // the impacts before t_r
  while (before < run.size() && run[before].t < release) ++before;
  const double rho = self_similar->remaining_ratio, mu = self_similar->multiplier;
  for (std::size_t k = 0; k + 2 < before; ++k) {
    const double s0 = release - run[k].t, s1 = release - run[k + 1].t, s2 = release - run[k + 2].t;
    const double q0 = s1 / s0, q1 = s2 / s1;
    result.by_index.push_back(((q1 - rho) - (q0 - rho) * q0) / std::pow(mu, static_cast<double>(k)));
  }
  const auto k0 = static_cast<std::size_t>(std::floor(self_similar->index));
  if (result.by_index.size() < k0 + 2) return result;
  const double m0 = result.by_index[k0], m1 = result.by_index[k0 + 1];
  const double f = self_similar->index - std::floor(self_similar->index);
  result.margin = (1.0 - f) * m0 + f * m1;
  result.spread = std::fabs(m1 - m0);
  return result;
}

namespace {

// The orbit from the release at p, from a state x near it: the map's image
// where x's chatter completes (then evaluated again from there), x itself
// where it does not.
struct Iterate {
  OrbitPoint x;
  double p = 0.0;
  OrbitEvaluation orbit;
};

std::optional<Iterate> release_flight(const OrbitAt& orbit_at, OrbitPoint x, double p) {
  OrbitEvaluation orbit = orbit_at(x, p);
  if (!orbit.completed) return std::nullopt;
  if (orbit.chatter_side > 0) {
    x = orbit.image;
    orbit = orbit_at(x, p);
    if (!orbit.completed) return std::nullopt;
  }
  return Iterate{std::move(x), p, std::move(orbit)};
}

// The margin at index k (k < 0: at K, blended).
double margin_of(const OrbitEvaluation& orbit, int k) {
  if (k < 0) return orbit.chatter_margin;
  const auto index = static_cast<std::size_t>(k);
  return index < orbit.chatter_margins.size() ? orbit.chatter_margins[index]
                                              : std::numeric_limits<double>::quiet_NaN();
}

// x_r at p: from b's state along the slope dx_dp
OrbitPoint extrapolated(const Iterate& b, const OrbitPoint& dx_dp, double p) {
  OrbitPoint x = b.x;
  for (std::size_t i = 0; i < x.size(); ++i) x[i] += dx_dp[i] * (p - b.p);
  return x;
}

// The slope of x_r between two iterates.
OrbitPoint slope_between(const Iterate& a, const Iterate& b) {
  OrbitPoint slope(a.x.size());
  for (std::size_t i = 0; i < slope.size(); ++i) slope[i] = (b.x[i] - a.x[i]) / (b.p - a.p);
  return slope;
}

}  // namespace

ChatterOnset solve_chatter_onset(const OrbitAt& orbit_at, const OrbitPoint& x0, double p0,
                                 const OrbitPoint& x1, double p1) {
  ChatterOnset onset;
  const std::optional<Iterate> first = release_flight(orbit_at, x0, p0);
  const std::optional<Iterate> second = release_flight(orbit_at, x1, p1);
  if (!first || !second || !std::isfinite(second->orbit.chatter_index) || first->p == second->p)
    return onset;
  Iterate previous = *first, current = *second;
  // x_r's slope, from the last two iterates at least 1e-9 apart (closer
  // ones would give it no digits)
  OrbitPoint dx_dp = slope_between(previous, current);
  std::vector<int> stages;
  for (int k = 2; k < static_cast<int>(std::floor(current.orbit.chatter_index)); k += 2)
    stages.push_back(k);
  stages.push_back(-1);
  double last_step = INFINITY;
  double separation = std::fabs(p1 - p0);
  for (const int k : stages) {
    // a second point `separation` from the last estimate
    if (std::fabs(previous.p - current.p) < 0.5 * separation) {
      const double p = current.p - separation;
      const auto other = release_flight(orbit_at, extrapolated(current, dx_dp, p), p);
      if (!other) return onset;
      previous = *other;
    }
    const double stage_start = current.p;
    for (int iteration = 0; iteration < 20; ++iteration) {
      const double m0 = margin_of(previous.orbit, k), m1 = margin_of(current.orbit, k);
      if (!std::isfinite(m0) || !std::isfinite(m1) || m0 == m1) return onset;
      if (m1 == 0.0) {
        last_step = 0.0;
        break;
      }
      const double p = current.p - m1 * (current.p - previous.p) / (m1 - m0);
      const auto next = release_flight(orbit_at, extrapolated(current, dx_dp, p), p);
      if (!next) return onset;
      last_step = std::fabs(p - current.p);
      previous = std::move(current);
      current = *next;
      if (std::fabs(current.p - previous.p) > 1e-9 * (1.0 + std::fabs(p)))
        dx_dp = slope_between(previous, current);
      if (last_step <= 1e-13 * (1.0 + std::fabs(p))) break;
    }
    // the next index's linear range is about 1/μ² of this one's: its two
    // points a hundredth of this stage's move apart
    separation = std::max(1e-2 * std::fabs(current.p - stage_start),
                          1e-11 * (1.0 + std::fabs(current.p)));
  }
  if (!(last_step <= 1e-10 * (1.0 + std::fabs(current.p)))) return onset;
  const double slope =
      std::fabs((current.orbit.chatter_margin - previous.orbit.chatter_margin) /
                (current.p - previous.p));
  const double spread = std::isfinite(current.orbit.chatter_spread) && slope > 0.0
                            ? current.orbit.chatter_spread / slope
                            : 0.0;
  onset.found = true;
  onset.state = current.x;
  onset.parameter = current.p;
  onset.error_estimate = last_step + spread;
  onset.orbit = std::move(current.orbit);
  return onset;
}

}  // namespace impactlab
