#include <impactlab/api/run_record.hpp>

#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/scene_record.hpp>

namespace impactlab {

namespace {

// What each of the run's events.csv columns holds, with its unit.
nlohmann::json event_column_units(const EventColumns& columns, const std::string& q_name) {
  const nlohmann::json every = {
      {"t", "s"},
      {"kind", "impact | grazing | accumulation | contact_start | contact_end | "
               "slip_reversal | painleve"},
      {"wall", "+1 / -1, 0 for none"},
      {"q", q_name},
      {"qdot_before", "d" + q_name + "/dt before the event"},
      {"qdot_after", "d" + q_name + "/dt after the event"},
      {"normal_impulse", "N s"},
      {"tangential_velocity", "m/s"},
      {"normal_force", "N"},
      {"friction_work", "J, cumulative over contact phases since t0"},
      {"instantaneous_residual",
       "m/s, pendulum Model P impacts: the paper's Eq. 26 residual (0: instantaneous)"},
      {"sliding_residual", "m/s, pendulum Model P impacts: the paper's Eqs. 21-22 residual (Fig. 4)"},
      {"tangential_velocity_after", "m/s, just after an impact (rigid model)"},
      {"accumulation_error",
       "s, accumulations: bound on the error of the accumulation time "
       "(contact/accumulation.hpp)"}};
  nlohmann::json units = nlohmann::json::object();
  for (const std::string_view name : columns.names())
    units[std::string(name)] = every.at(std::string(name));
  return units;
}

}  // namespace

nlohmann::json run_record(const Scene& scene, const RunOutput& output) {
  const SceneSchema& schema = scene_schema(scene);
  const std::string q_name(schema.main_coordinate);
  nlohmann::json record = {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"scene", scene_record(scene)},
      {"model", scene.values.contains("model") ? to_text(scene.values.at("model")) : "newton"},
      {"integrator",
       {{"method", scene.text("integrator.method")},
        {"rtol", scene.number("integrator.rtol")},
        {"atol", scene.number("integrator.atol")}}},
      {"run",
       {{"t0_s", output.t0},
        {"t_end_s", output.t_end},
        {"t_final_s", output.t_final},
        {"termination", to_string(output.termination)}}},
      {"counts",
       {{"steps", output.steps},
        {"rhs_evaluations", output.rhs_evaluations},
        {"impacts", output.impacts},
        {"contact_phases", output.contact_phases},
        {"accumulations", output.accumulations},
        {"grazings", output.grazings},
        {"events", output.event_count}}},
      {"accumulation",
       {{"largest_time_error_s", output.largest_accumulation_error},
        {"time_tolerance_s", accumulation_time_tolerance(scene)},
        {"note", "error bound of each accumulation time: events.csv accumulation_error"}}},
      {"wall_time_s", output.wall_time},
      {"derived", output.derived},
      {"columns",
       {{"events.csv", event_column_units(output.event_columns, q_name)},
        {"trajectory.csv", {{"t", "s"}, {"q", q_name},
                            {"qdot", "d" + q_name + "/dt"},
                            {"mode", "mode of the hybrid system"}}}}},
  };
  // what to do about a stopped run, where the oscillator knows
  if (!output.stop_advice.empty()) record["run"]["stop_advice"] = output.stop_advice;
  return record;
}

}  // namespace impactlab
