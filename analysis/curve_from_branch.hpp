// The two-parameter curve of a located point of a branch of a scene's
// system (curve_continuation.hpp's driver on the system's section maps):
// which point it starts from, the section map at each value of the second
// parameter, and, for a grazing of the impact section's own impact, the
// curve followed on the stroboscopic map and carried back onto the section.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/continuation_problem.hpp>
#include <impactlab/analysis/curve_continuation.hpp>
#include <impactlab/analysis/flow_setup.hpp>
#include <impactlab/analysis/stroboscopic_map_problem.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

// The curve of the first located point of job.curve_type (without one: the
// first fold, period doubling or grazing point) of branch `index`, in (job.parameter,
// job.second_parameter), into `curve`; false, with why in `note`, where the
// branch has none. map_at(scene, period) is the branch's section map of the
// system `scene` describes, continued in job.parameter (stroboscopic or
// impact section). On the impact section, a grazing of the section's own
// impact is followed on the stroboscopic map half a forcing period after the
// impact (as the branch located it: that section is tangent to the flow
// there), and each point is carried back onto the impact section:
// (φ, q̇⁻) = (phase + ω (t_g − nT), q̇(t_g)), graze time 0.
template <HasJacobian System, class SystemAt, class MapAt>
bool continue_curve_of(const ContinuationJobResult& result, std::size_t index, CurveResult& curve,
                       std::string& note, SystemAt system_at, MapAt map_at,
                       typename System::Mode flight_mode, const Scene& scene,
                       const ContinuationJob& job, const FlowSetup& setup, double omega) {
  const ContinuationResult& branch = result.branches.at(index).result;
  const int period = result.branches[index].period;
  // the type asked for; without one, the first fold, period doubling or grazing
  const auto wanted = [&](const BifurcationPoint& p) {
    const std::optional<CurveType> type = curve_type_of(p);
    if (!p.located || !type) return false;
    if (job.curve_type) return *type == *job.curve_type;
    return *type == CurveType::fold || *type == CurveType::period_doubling ||
           *type == CurveType::grazing;
  };
  const auto found = std::find_if(branch.points.begin(), branch.points.end(), wanted);
  if (found == branch.points.end()) {
    note = "no located " +
           (job.curve_type ? std::string(to_string(*job.curve_type))
                           : std::string("fold, period doubling or grazing")) +
           " point on the branch to start the curve from";
    return false;
  }
  CurveRequest request;
  request.type = *curve_type_of(*found);
  request.from1 = job.from;
  request.to1 = job.to;
  request.from2 = job.second_from;
  request.to2 = job.second_to;
  request.p1 = found->parameter;
  request.state = found->state;
  request.graze_time = found->graze_time;
  request.graze_witness = found->graze_witness;
  request.max_points = job.numerics.max_points;
  request.tolerance = job.numerics.tolerance;
  request.normal_forms = job.numerics.normal_forms;
  // the branch's largest step, as a fraction of the first parameter's range
  if (job.numerics.max_step > 0.0) request.max_step = job.numerics.max_step / std::fabs(job.to - job.from);
  const auto scene_at = [scene, job](double p2) {
    Scene at = scene;
    at.values[job.second_parameter] = p2;
    return at;
  };
  const ContinuationProblem at_start = map_at(scene_at(job.second_from), period);
  const bool section_wall_graze = request.type == CurveType::grazing && at_start.section_witness >= 0 &&
                                  found->graze_witness == at_start.section_witness;
  TwoParameterProblem problem;
  double strobe_phase = 0.0;  // rad: the stroboscopic section of a section-wall graze
  if (section_wall_graze) {
    strobe_phase = found->state[0] + std::numbers::pi;
    const auto carried = at_start.to_strobe(found->state, found->parameter, strobe_phase);
    if (!carried) {
      note = "the grazing point could not be carried to the stroboscopic section";
      return false;
    }
    Scene at = scene_at(job.second_from);
    at.values[job.parameter] = found->parameter;
    const double span = period * 2.0 * std::numbers::pi / forcing_omega_of(system_at(at));
    request.state = *carried;
    request.graze_time = span - 0.5 * span / period;
    problem.at = [scene_at, job, system_at, flight_mode, setup, omega, period,
                  strobe_phase](double p2) {
      auto make_system = [scene = scene_at(p2), job, system_at](double p1) {
        Scene at = scene;
        at.values[job.parameter] = p1;
        return system_at(at);
      };
      return stroboscopic_map_problem<System>(make_system, flight_mode, setup, strobe_phase,
                                              period, omega);
    };
  } else {
    problem.at = [scene_at, map_at, period](double p2) { return map_at(scene_at(p2), period); };
  }
  curve = continue_curve(problem, request);
  if (section_wall_graze) {
    // back onto the impact section
    for (CurvePoint& point : curve.curve) {
      const ContinuationProblem strobe = problem.at(point.p2);
      Scene at = scene_at(point.p2);
      at.values[job.parameter] = point.p1;
      const double point_omega = forcing_omega_of(system_at(at));
      const double span = period * 2.0 * std::numbers::pi / point_omega;
      const double half_width = 0.1 * strobe.forcing_period_at_p;
      const GapSample touch = strobe.gap_at(
          point.state, point.p1, strobe_phase,
          ContactWindow{found->graze_witness, point.graze_time - half_width,
                        point.graze_time + half_width},
          point.graze_time);
      point.state = {strobe_phase + point_omega * (point.graze_time - span),
                     touch.completed ? touch.state[1] : std::numeric_limits<double>::quiet_NaN()};
      point.graze_time = 0.0;
    }
  }
  return true;
}

// The curve of type `through` (curve_through) through a codimension-two
// point of a curve (`switch`): at a grazing–period-doubling point the
// period-doubling curve of the orbit it grazes, at a grazing–fold point its
// fold curve, followed from the point towards job.second_from (the side the
// grazing curve came from) on the stroboscopic section; false, with why in `note`, where it cannot start.
template <class MapAt>
bool continue_curve_from_point(const CodimensionTwoPoint& point, CurveType through, int period,
                               CurveResult& curve, std::string& note, MapAt map_at,
                               const Scene& scene, const ContinuationJob& job) {
  if (job.impact_wall != 0) {
    note = "a curve through a codimension-two point is followed on the stroboscopic section only";
    return false;
  }
  CurveRequest request;
  request.type = through;
  request.from1 = job.from;
  request.to1 = job.to;
  request.from2 = point.p2;
  request.to2 = job.second_from;
  request.p1 = point.p1;
  request.state = point.state;
  request.graze_time = point.graze_time;
  request.graze_witness = point.graze_witness;
  request.max_points = job.numerics.max_points;
  request.tolerance = job.numerics.tolerance;
  request.normal_forms = job.numerics.normal_forms;
  if (job.numerics.max_step > 0.0) request.max_step = job.numerics.max_step / std::fabs(job.to - job.from);
  TwoParameterProblem problem;
  problem.at = [scene, job, map_at, period](double p2) {
    Scene at = scene;
    at.values[job.second_parameter] = p2;
    return map_at(at, period);
  };
  curve = continue_curve(problem, request);
  return true;
}

}  // namespace impactlab
