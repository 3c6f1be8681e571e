#include <impactlab/api/section_record.hpp>

#include <string>

namespace impactlab {

nlohmann::json section_request_record(std::string_view section_text,
                                      const SectionRequest& request) {
  const bool counts_impacts = request.transient_impacts > 0;
  nlohmann::json record = {
      {"section", std::string(section_text)},
      {"transient_periods", counts_impacts ? 0.0 : request.transient_periods},
      {"transient_impacts", request.transient_impacts},
      {"points", request.points}};
  if (counts_impacts || !request.settle) {
    record["settling"] = nullptr;
    return record;
  }
  record["settling"] = {
      {"rule",
       "at least transient_periods forcing periods, then windows of window_periods until the "
       "stroboscopic points (q, qdot) settle: some period p <= max_period has "
       "|y_{k+p} - y_k| <= tolerance (1 + max |y|) over the whole window (settled); the "
       "transient also ends where the points neither repeat nor still converge (not_periodic: "
       "chaos, a torus, a longer period), and at max_periods (not_settled)"},
      {"min_periods", request.transient_periods},
      {"max_periods", request.max_transient_periods},
      {"window_periods", request.settle_window_periods},
      {"tolerance", request.settle_tolerance},
      {"max_period", request.settle_max_period}};
  return record;
}

}  // namespace impactlab
