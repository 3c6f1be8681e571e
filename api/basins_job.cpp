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
  // the entropies' boxes fit in the grid
  const int shorter_side = std::min(plan.axes[0].count, plan.axes[1].count);
  if (spec.entropy_box && *spec.entropy_box < 1)
    throw BadInput("entropy_box", std::to_string(*spec.entropy_box), "must be a whole number >= 1");
  if (spec.entropy_box && *spec.entropy_box > shorter_side)
    throw BadInput("entropy_box", std::to_string(*spec.entropy_box),
                   fmt::format("larger than the grid's shorter side ({} points)", shorter_side));
  plan.entropy_box = spec.entropy_box.value_or(std::min(default_entropy_box, shorter_side));
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
  table.measures =
      basin_measures(table.attractor, plan.axes[0].count, plan.axes[1].count, plan.entropy_box);
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

namespace {

// a number for JSON: nan (undefined) as null
nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

nlohmann::json basin_measures_record(const BasinMeasures& m) {
  return {
      {"box_size", m.box_size},
      {"boxes", m.boxes},
      {"boundary_boxes", m.boundary_boxes},
      {"labels", m.labels},
      {"basin_entropy", finite_or_null(m.basin_entropy)},
      {"boundary_basin_entropy", finite_or_null(m.boundary_basin_entropy)},
      {"boundary_is_fractal_by_log2", m.fractal_by_log2},
      {"scales", m.scales},
      {"uncertain_fraction", m.uncertain_fraction},
      {"uncertainty_exponent", finite_or_null(m.uncertainty_exponent)},
      {"uncertainty_exponent_error", finite_or_null(m.uncertainty_exponent_error)},
      {"boundary_dimension", finite_or_null(m.boundary_dimension)},
      {"meaning",
       {{"box_size", "side of the boxes that tile the grid (grid points); points past the last "
                     "whole box are left out"},
        {"boxes", "whole boxes"},
        {"boundary_boxes", "N_b: boxes holding more than one attractor"},
        {"labels", "distinct attractor ids in the grid; 0 (none found) counts as one"},
        {"basin_entropy", "S_b: mean over all boxes of -sum p ln p over the box's attractor "
                          "shares (nats; 0 to ln(labels); Daza et al. 2016)"},
        {"boundary_basin_entropy", "S_bb: the same mean over the N_b boundary boxes (nats); "
                                   "null without boundary boxes"},
        {"boundary_is_fractal_by_log2", "S_bb > ln 2: sufficient for a fractal boundary"},
        {"scales", "k: distances at which neighbours are compared (grid points), 1, 2, 4, ... "
                   "up to a quarter of the shorter side"},
        {"uncertain_fraction", "f(k): share of grid points with a neighbour k points away along "
                               "either axis that settles on another attractor"},
        {"uncertainty_exponent", "alpha: least-squares slope of ln f against ln k (Grebogi et "
                                 "al. 1983); 1 for a smooth boundary, below 1 for a fractal one; "
                                 "null without a boundary"},
        {"uncertainty_exponent_error", "standard error of alpha from the fit; null with fewer "
                                       "than 3 scales"},
        {"boundary_dimension", "d = 2 - alpha: box dimension of the basin boundary"}}}};
}

std::string basin_measures_line(const BasinMeasures& m) {
  return fmt::format(
      "basin entropy S_b = {:.4f}, boundary basin entropy S_bb = {:.4f} ({} of {} boxes of {}x{}; "
      "{} ln 2), uncertainty exponent alpha = {:.3f} +- {:.3f} (boundary dimension {:.3f})",
      m.basin_entropy, m.boundary_basin_entropy, m.boundary_boxes, m.boxes, m.box_size,
      m.box_size, m.fractal_by_log2 ? "above" : "not above", m.uncertainty_exponent,
      m.uncertainty_exponent_error, m.boundary_dimension);
}

}  // namespace impactlab
