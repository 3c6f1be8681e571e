// What `continue` writes of a located grazing point's discontinuity map and
// normal form (analysis/grazing_normal_form.hpp), the same for the CLI's
// files and Python's result: the extra columns of points.csv and the entry of
// grazing.json (one file per run, an entry per grazing point, in the order of
// points.csv's rows; docs/analysis.md, "Discontinuity map and normal form at
// a grazing point").
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include <impactlab/analysis/continuation.hpp>

namespace impactlab {

// points.csv's columns after `note`: scenario (empty on a row that is no
// grazing, "unavailable" where the normal form is not), impacting_side (±1:
// the sign of p − p_g past the graze), impact_speed_coefficient (c: the first
// impact past the graze at V ≈ c √|p − p_g|), period_one_speed_slope (the
// period-1 impacting orbit born there: V₁ ≈ slope |p − p_g|), period_one_side.
inline constexpr const char* grazing_csv_header =
    "scenario,impacting_side,impact_speed_coefficient,period_one_speed_slope,period_one_side";
std::string grazing_csv_fields(const BifurcationPoint& point);

// grazing.json's entry of a grazing point (its normal form, scenario and
// scalings), `row` its row in points.csv (from 0), `branch` and `period` those
// of its branch; `parameter` the continued key's name.
nlohmann::json grazing_record(const BifurcationPoint& point, const std::string& parameter,
                              int row, int branch, int period);

// grazing.json's column notes: what each field is, with its unit.
nlohmann::json grazing_fields();

}  // namespace impactlab
