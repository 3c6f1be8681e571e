// When a transient has settled: the test a section run applies to the
// stroboscopic points of its transient's last window before it starts to
// record (analysis/run_section.hpp), so that a sweep labels the attractor and
// not a state still on its way there.
//
// The window's points y_0 … y_{W−1} are (q, q̇) once per forcing period. For
// each candidate period p the mismatch m_p(k) = |y_{k+p} − y_k| / s, with
// s = 1 + max_k |y_k| (the scale the sweep's period test uses), says how far
// the points are from repeating after p periods.
//   settled       m_p(k) ≤ tolerance for every k;
//   converging    m_p still shrinks: its logarithm falls along the window on
//                 lines of one slope, one line for each of the p points of
//                 the orbit (R² ≥ 0.9: a real multiplier, however slow), or
//                 its largest value over the window's second half is at
//                 most half that over the first (a spiral's envelope);
// and the shortest p that is either decides. Points approaching a period-2
// orbit at the multiplier −0.9967 repeat after 4 periods far better than
// after 2, but they are still converging. Where no p up to max_period is
// either, the points are
//   not_periodic  a chaotic or quasi-periodic motion, or a period longer
//                 than the longest looked for: running longer would not
//                 change its record, so the transient ends here too.
#pragma once

#include <vector>

#include <impactlab/analysis/section.hpp>

namespace impactlab {

enum class SettlingVerdict { settled, converging, not_periodic };

// The verdict on `window` (consecutive stroboscopic points, one forcing
// period apart), looking at periods 1 … max_period (at most half the
// window); `tolerance` is relative to the scale s above.
SettlingVerdict settling_verdict(const std::vector<SectionPoint>& window, int max_period,
                                 double tolerance);

}  // namespace impactlab
