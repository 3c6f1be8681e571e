#include "section_options.hpp"
#include "program_files.hpp"

#include <iostream>

#include <fmt/format.h>

#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/platform/run_program.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab::cli {

void SectionOptions::add_to(CLI::App& command, const std::string& points_help) {
  command.add_option("scene", scene.scene, "built-in scene name or path to a scene file (.toml)")
      ->capture_default_str();
  command.add_option("--set", scene.assignments,
                     "KEY=VALUE, repeatable: a parameter (omega, V0, e_n, ...) or a dotted key");
  command.add_option("--out", scene.out, "output directory (default out/<scene>)");
  command.add_flag("--quiet", scene.quiet, "print nothing but errors");
  command.add_option("--section", section,
                     "strobe[:PHASE] (forcing phase wt mod 2pi, rad), impact[:WALL] "
                     "(+1, -1, 0 = any wall), or a user-given section q=LEVEL[:up|down|both] "
                     "or qdot=LEVEL[:up|down|both]")
      ->capture_default_str();
  auto* by_impacts = command.add_option("--transient-impacts", transient_impacts,
                                        "discard this many impacts instead of periods")
                        ->check(count_in(0, 1000000000));
  command.add_option("--transient", transient, "forcing periods discarded first")
      ->check(number_in(0.0, 1e9))
      ->capture_default_str()
      ->excludes(by_impacts);
  command.add_option("--points", points, points_help)
      ->check(count_in(1, 100000000))
      ->capture_default_str();
  command.add_flag("--plot", plot, "also write a PNG (matplotlib through /usr/bin/python3)");
}

SectionRequest SectionOptions::request() const {
  SectionRequest request;
  request.section = parse_section(section, "--section");
  request.transient_periods = transient;
  request.transient_impacts = transient_impacts;
  request.points = points;
  return request;
}

nlohmann::json SectionOptions::record() const {
  return {{"section", section},
          {"transient_periods", transient_impacts > 0 ? 0.0 : transient},
          {"transient_impacts", transient_impacts},
          {"points", points}};
}

bool plot_with_python(const std::string& kind, const std::filesystem::path& csv,
                      const std::filesystem::path& png, const std::vector<std::string>& extra) {
  const std::filesystem::path script =
      program_file("scripts/plot_sweep.py");
  const std::filesystem::path python = "/usr/bin/python3";
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
