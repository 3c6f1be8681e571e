// What meta.json records of a section request (poincare, sweep, basins): the
// section as given, the transient (exact, or the settling rule with its
// bounds) and the points recorded. The CLI and the Python module write the
// same record.
#pragma once

#include <string_view>

#include <nlohmann/json.hpp>

#include <impactlab/analysis/section.hpp>

namespace impactlab {

nlohmann::json section_request_record(std::string_view section_text,
                                      const SectionRequest& request);

}  // namespace impactlab
