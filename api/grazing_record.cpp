#include <impactlab/api/grazing_record.hpp>

#include <cmath>
#include <complex>
#include <vector>

#include <impactlab/io/output.hpp>

namespace impactlab {

namespace {

// a number, or null where it is not finite (JSON has no NaN)
nlohmann::json number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json numbers(const std::vector<double>& values) {
  nlohmann::json list = nlohmann::json::array();
  for (double value : values) list.push_back(number(value));
  return list;
}

nlohmann::json rows(const MonodromyMatrix& m) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& row : m) list.push_back(numbers(row));
  return list;
}

nlohmann::json complex_numbers(const std::vector<std::complex<double>>& values) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& value : values) list.push_back({number(value.real()), number(value.imag())});
  return list;
}

}  // namespace

std::string grazing_csv_fields(const BifurcationPoint& point) {
  if (point.type != BifurcationType::grazing) return ",,,,";
  if (!point.normal_form || !point.normal_form->available) return "unavailable,,,,";
  const GrazingNormalForm& form = *point.normal_form;
  return std::string(to_string(form.scenario)) + ',' + std::to_string(form.impacting_side) + ',' +
         csv_field(form.root_coefficient) + ',' + csv_field(form.period_one_slope) + ',' +
         std::to_string(form.period_one_side);
}

nlohmann::json grazing_record(const BifurcationPoint& point, const std::string& parameter,
                              int row, int branch, int period) {
  nlohmann::json record = {{"row", row},
                           {"branch", branch},
                           {"period", period},
                           {parameter, point.parameter},
                           {"graze_time", number(point.graze_time)},
                           {"witness", point.graze_witness},
                           {"kind", point.note}};
  if (!point.normal_form) {
    record["available"] = false;
    record["reason"] = "not computed (normal_forms off)";
    return record;
  }
  const GrazingNormalForm& form = *point.normal_form;
  record["available"] = form.available;
  if (!form.note.empty()) record["reason"] = form.note;
  if (!form.available) return record;
  const DiscontinuityMap& map = form.map;
  record["section_phase"] = form.phase;
  record["state"] = numbers(form.state);
  record["discontinuity_map"] = {{"gap_acceleration", number(map.gap_acceleration)},
                                 {"gap_jerk", number(map.gap_jerk)},
                                 {"gap_gradient", numbers(map.gap_gradient)},
                                 {"jump", numbers(map.jump)},
                                 {"leading", numbers(map.leading)},
                                 {"next", numbers(map.next)}};
  record["normal_form"] = {{"linear", rows(form.linear)},
                           {"eigenvalues", complex_numbers(form.eigenvalues)},
                           {"parameter_vector", numbers(form.parameter_vector)},
                           {"gap_gradient", numbers(form.gap_gradient)},
                           {"gap_parameter", number(form.gap_parameter)},
                           {"root_vector", numbers(form.root_vector)}};
  record["gap_per_parameter"] = number(form.gap_per_parameter);
  record["impacting_side"] = form.impacting_side;
  record["impact_speed_coefficient"] = number(form.root_coefficient);
  record["period_one"] = {{"side", form.period_one_side},
                          {"speed_slope", number(form.period_one_slope)}};
  record["kick_gaps"] = numbers(form.kick_gaps);
  record["dominant_product"] = number(form.dominant_product);
  record["scenario"] = to_string(form.scenario);
  record["rule"] = to_string(form.rule);
  record["other_side"] = form.other_side;
  record["period_sequence"] = form.period_sequence;
  nlohmann::json attractors = nlohmann::json::array();
  for (const NormalFormAttractor& a : form.attractors)
    attractors.push_back({{"distance", a.distance},
                          {parameter, form.parameter + a.distance},
                          {"kind", a.kind},
                          {"period", a.period},
                          {"impacts", a.impacts},
                          {"max_impact_speed", number(a.max_impact_speed)},
                          {"impact_speeds", numbers(a.impact_speeds)},
                          {"lyapunov", number(a.lyapunov)}});
  record["attractors"] = attractors;
  nlohmann::json further = nlohmann::json::array();
  for (std::size_t j = 0; j < form.further_touches.size(); ++j) {
    const FurtherTouch& touch = form.further_touches[j];
    further.push_back({{"section_phase", touch.phase},
                       {"after", touch.after},
                       {"witness", touch.witness},
                       {"state", numbers(touch.map.state)},
                       {"gap_parameter", number(touch.gap_parameter)},
                       {"discontinuity_map",
                        {{"gap_acceleration", number(touch.map.gap_acceleration)},
                         {"gap_jerk", number(touch.map.gap_jerk)},
                         {"gap_gradient", numbers(touch.map.gap_gradient)},
                         {"jump", numbers(touch.map.jump)},
                         {"leading", numbers(touch.map.leading)},
                         {"next", numbers(touch.map.next)}}}});
  }
  record["further_touches"] = further;
  if (!further.empty()) {
    nlohmann::json segments = nlohmann::json::array();
    for (std::size_t j = 0; j < form.segment_flows.size(); ++j)
      segments.push_back({{"flow", rows(form.segment_flows[j])},
                          {"parameter_vector", numbers(form.segment_parameter_vectors[j])}});
    record["segments"] = segments;
  }
  return record;
}

nlohmann::json grazing_fields() {
  return {
      {"row", "the point's row in points.csv (from 0)"},
      {"kind", "which grazing: a flight extremum touches the wall, or an impact velocity goes "
               "to zero (points.csv's note)"},
      {"section_phase", "rad: the forcing phase omega t_g of the touch; the normal form lives on "
                        "the stroboscopic section omega t = section_phase (mod 2 pi), its state "
                        "xi = x - x_g the deviation from the touch, mu = p - p_g"},
      {"state", "x_g: the orbit's state at the touch (the gap zero, its rate zero)"},
      {"discontinuity_map",
       "Nordmark's zero-time discontinuity map at the touch: D(y) = y for h(y) >= 0, "
       "y + leading sqrt(-h) + next h for h < 0, h = gap_gradient . (y - x_g) (the gap's unit); "
       "gap_acceleration a = h'' (> 0), gap_jerk b = h''' along the orbit (gap unit / s^2, s^3); "
       "jump W: the reset's x+ - x- per unit of the normal velocity before it; leading = "
       "-sqrt(2a) W; next = 2 J W - (2b/3a) W"},
      {"normal_form",
       "one orbit period (n forcing periods) of the stroboscopic map at section_phase: xi -> "
       "linear xi + parameter_vector mu, plus root_vector sqrt(-h) where h = gap_gradient . xi "
       "+ gap_parameter mu < 0; eigenvalues of `linear` as [re, im], largest modulus first"},
      {"gap_per_parameter", "g_mu = C (I - N)^-1 M + d: the virtual orbit's gap at the touch per "
                            "unit of mu (gap unit per parameter unit)"},
      {"impacting_side", "+1 or -1: the sign of mu past the graze (where the virtual orbit "
                         "penetrates the wall: -sign g_mu)"},
      {"impact_speed_coefficient",
       "c = sqrt(2 a |g_mu|): the first impact past the graze has the normal speed c sqrt(|mu|) "
       "(gap rate units); the impact speeds of the attractor born there scale so"},
      {"period_one", "the period-1 impacting orbit born at the graze (a maximal orbit of the "
                     "normal form, one impact an orbit): on side `side` (0: none) its impact "
                     "speed is speed_slope |mu|; near the graze it is unstable"},
      {"kick_gaps", "e_k = C N^(k-1) E, k = 1..24: the gap k orbit periods after an impact of "
                    "unit sqrt(-h); a negative one kicks the orbit back into the wall"},
      {"dominant_product", "K = C P1 E for a real dominant eigenvalue (P1 its spectral "
                           "projector): the product whose sign decides the period-n orbits"},
      {"scenario", "from the normal form iterated at 25 distances past the graze: "
                   "period_adding, period_adding_with_chaos, chaos, stable_impacting_orbit, "
                   "jump (no attractor near the grazing orbit), not_applicable"},
      {"rule", "from the eigenvalues (Nordmark's square-root map): lambda1 real in (0, 1/4) "
               "period_adding, (1/4, 2/3) period_adding_with_chaos, (2/3, 1) chaos, with every "
               "kick_gap >= 0; jump where one is negative; not_applicable for complex ones"},
      {"other_side", "what remains on the side without impacts (the non-impacting orbit)"},
      {"period_sequence", "the periods (orbit periods) of the periodic attractors at the "
                          "distances, the distance falling: the period-adding sequence"},
      {"further_touches",
       "other walls touched by the same virtual orbit at the graze (a symmetric orbit between "
       "two walls): each one's phase, time after the first touch (s), state, ZDM and d; the "
       "map is then the composition round the orbit of each touch's ZDM and `segments` (the "
       "flow and parameter vector from each touch to the next, the first touch's first)"},
      {"attractors", "the normal form's attractor at each distance (mu, and the parameter "
                     "p_g + mu): kind (periodic, chaotic, aperiodic, escapes), period, impacts "
                     "per period, the impact speeds (gap rate units) and the Lyapunov exponent "
                     "per orbit period"}};
}

}  // namespace impactlab
