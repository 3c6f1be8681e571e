#include <impactlab/api/basins_job.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include <impactlab/io/bad_input.hpp>

namespace impactlab {

SweepPlan make_basins_plan(const BasinsSpec& spec, const Scene& scene, const SceneSchema& schema) {
  // the grid keys named by the options that gave them
  for (const auto& [option, text] : {std::pair{&spec.x_key, &spec.x}, std::pair{&spec.y_key, &spec.y}}) {
    const SweepAxis axis = parse_axis(*text, *option);
    const auto key = std::find_if(schema.keys.begin(), schema.keys.end(),
                                  [&](const KeySpec& k) { return k.key == axis.name; });
    if (key == schema.keys.end() || key->is_text)
      throw BadInput(*option, axis.name,
                     fmt::format("not a numeric key of oscillator {}", schema.oscillator));
  }
  const std::string y_name = parse_axis(spec.y, spec.y_key).name;
  if (parse_axis(spec.x, spec.x_key).name == y_name)
    throw BadInput(spec.y_key, y_name, fmt::format("must differ from {}'s key", spec.x_key));
  if (!(spec.attractor_tolerance > 0.0) || !std::isfinite(spec.attractor_tolerance))
    throw BadInput(spec.attractor_tolerance_key, fmt::format("{}", spec.attractor_tolerance),
                   "must be a finite number > 0");
  SweepSpec sweep;
  sweep.params = {spec.x, spec.y};
  sweep.section = spec.section;
  sweep.lyapunov = spec.lyapunov;  // off unless asked for
  sweep.period_tolerance = spec.period_tolerance;
  sweep.max_period = spec.max_period;
  sweep.param_key = spec.grid_key;
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
  for (const SweepRecord* r : in_grid_order) {
    table.x.push_back(plan.axes[0].value(r->index[0]));
    table.y.push_back(plan.axes[1].value(r->index[1]));
    table.period.push_back(r->classification.period);
    table.impacts_per_period.push_back(r->classification.impacts_per_period);
    table.contact.push_back(r->classification.contact ? 1 : 0);
    table.termination.push_back(r->result.termination);
  }
  return table;
}

}  // namespace impactlab
