#include <impactlab/api/basins_job.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include <impactlab/api/job_options.hpp>
#include <impactlab/api/model_keys.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab {

SweepPlan make_basins_plan(const BasinsSpec& spec, const Scene& scene, const SceneSchema& schema) {
  // the grid keys named by the options that gave them
  for (const auto& [option, text] : {std::pair{"x", &spec.x}, std::pair{"y", &spec.y}}) {
    const SweepAxis axis = parse_axis(*text, option);
    const auto key = std::find_if(schema.keys.begin(), schema.keys.end(),
                                  [&](const KeySpec& k) { return k.key == axis.name; });
    if (key == schema.keys.end() || key->is_text)
      throw BadInput(option, axis.name,
                     fmt::format("not a numeric key of oscillator {}", schema.oscillator));
    refuse_unread_key(scene, schema, axis.name, option);
  }
  const std::string y_name = parse_axis(spec.y, "y").name;
  if (parse_axis(spec.x, "x").name == y_name)
    throw BadInput("y", y_name, "must differ from " + mention("x") + "'s key");
  if (!(spec.attractor_tolerance > 0.0) || !std::isfinite(spec.attractor_tolerance))
    throw BadInput("attractor_tol", fmt::format("{}", spec.attractor_tolerance),
                   "must be a finite number > 0");
  SweepSpec sweep;
  sweep.params = {spec.x, spec.y};
  sweep.section = spec.section;
  sweep.lyapunov = spec.lyapunov;  // off unless asked for
  sweep.period_tolerance = spec.period_tolerance;
  sweep.max_period = spec.max_period;
  sweep.param_key = "x/y";
  SweepPlan plan = make_sweep_plan(sweep, scene, schema);
  plan.follow_attractor = false;  // every point from the scene's state
  // basins tell attractors apart by their section points and write them
  // (attractors.csv): they are not classification-only
  plan.classification_integrator.reset();
  plan.classification_note =
      "the scene's integrator: basins tell attractors apart by their section points";
  plan.attractor_tolerance = spec.attractor_tolerance;
  return plan;
}

nlohmann::json basins_definition(const SweepPlan& plan, const Scene& scene,
                                 const SceneSchema& schema, const nlohmann::json& section_record) {
  nlohmann::json definition = sweep_definition(plan, scene, schema, section_record);
  definition["basins"] = true;
  definition["attractor_tolerance"] = plan.attractor_tolerance;
  return definition;
}

BasinsTable basins_table(const SweepPlan& plan, const std::vector<SweepTask>& tasks,
                         const std::map<SweepRecordKey, SweepRecord>& records) {
  std::vector<const SweepRecord*> in_grid_order;
  for (const auto& task : tasks)
    for (std::size_t p = 0; p < task.points.size(); ++p)
      in_grid_order.push_back(&records.at({task.id, static_cast<int>(p)}));
  BasinsTable table;
  table.map = identify_attractors(in_grid_order, plan.attractor_tolerance);
  table.attractor = table.map.attractor;
  table.lyapunov_dimension = lyapunov_dimension(plan, records);
  for (const SweepRecord* r : in_grid_order) {
    add_lyapunov_spectrum(table.lyapunov_spectrum, table.lyapunov_dimension, *r);
    table.x.push_back(plan.axes[0].value(r->index[0]));
    table.y.push_back(plan.axes[1].value(r->index[1]));
    table.period.push_back(r->classification.period);
    table.impacts_per_period.push_back(r->classification.impacts_per_period);
    table.contact.push_back(r->classification.contact ? 1 : 0);
    table.termination.push_back(r->result.termination);
    table.transient_end.push_back(r->result.transient_end);
  }
  return table;
}

AttractorRows attractor_rows(const BasinMap& map) {
  AttractorRows rows;
  const auto add = [&rows](int id, int period, double impacts_per_period, bool contact, double q,
                           double qdot, int basin_points) {
    rows.id.push_back(id);
    rows.period.push_back(period);
    rows.impacts_per_period.push_back(impacts_per_period);
    rows.contact.push_back(contact ? 1 : 0);
    rows.q.push_back(q);
    rows.qdot.push_back(qdot);
    rows.basin_points.push_back(basin_points);
  };
  const double none = std::nan("");
  if (map.unclassified > 0) add(0, 0, none, false, none, none, map.unclassified);
  for (const Attractor& a : map.attractors)
    add(a.id, a.period, a.impacts_per_period, a.contact, a.point[0], a.point[1], a.basin_points);
  return rows;
}

}  // namespace impactlab
