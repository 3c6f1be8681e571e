#include "section_options.hpp"
#include "program_files.hpp"

#include <iostream>

#include <fmt/format.h>

#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/platform/run_program.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab::cli {

void SectionOptions::add_to(TableOptions& table) {
  scene.add_scene(table);
  table.add("section", section);
  table.add("transient_impacts", transient_impacts);
  transient_option = table.add("transient", transient);
  table.add("max_transient", max_transient);
  table.add("points", points);
  table.add("plot", plot);
}

SectionRequest SectionOptions::request() const {
  SectionRequest request;
  request.section = parse_section(section, "section");
  // an explicit transient runs exactly; the default settles
  request.settle = !option_given(transient_option);
  if (!request.settle) request.transient_periods = transient;
  request.max_transient_periods = max_transient;
  request.transient_impacts = transient_impacts;
  request.points = points;
  return request;
}

bool plot_with_python(const std::string& kind, const std::filesystem::path& csv,
                      const std::filesystem::path& png, const std::vector<std::string>& extra) {
  const std::filesystem::path script =
      program_file("scripts/plot_sweep.py");
  const std::filesystem::path python = plot_python();
  if (!std::filesystem::exists(python) || !std::filesystem::exists(script)) {
    std::cerr << fmt::format("impactlab: warning: plot skipped ({} not found); the data are in {}\n",
                             std::filesystem::exists(python) ? script.string() : python.string(),
                             csv.string());
    return false;
  }
  // run it without a shell, so that no path needs quoting
  std::vector<std::string> arguments = {python.string(), script.string(), kind, csv.string(),
                                        png.string()};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  if (run_program(arguments) != 0) {
    std::cerr << fmt::format(
        "impactlab: warning: plot skipped (the plot script failed: is python3-matplotlib "
        "installed?); the data are in {}\n",
        csv.string());
    return false;
  }
  return true;
}

}  // namespace impactlab::cli
