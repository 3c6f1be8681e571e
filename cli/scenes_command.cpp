// `impactlab scenes [SCENE]`: the built-in scenes, or one scene's keys with
// value, unit, range and help, and where its models read different keys
// (api/model_keys.hpp), the models that read each key that not every model
// reads; the header names every model, the readers of the keys unmarked.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include <impactlab/api/model_keys.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include "command.hpp"
#include "commands.hpp"
#include "program_files.hpp"
#include "table_options.hpp"
#include <impactlab/io/builtin_scenes.hpp>

namespace impactlab::cli {

namespace {

int run_scenes(const std::string& name) {
  if (name.empty()) {
    for (const auto& builtin : builtin_scenes()) {
      const Scene scene = load_scene(builtin.name);
      std::cout << fmt::format("{:<16} {:<16} {}\n", builtin.name, scene.oscillator,
                               scene.text("description"));
    }
    // the model files that ship with the program (CMakeLists.txt copies
    // them beside it): a path is a scene name to every command
    const std::filesystem::path examples = program_file("oscillators/model_file/examples");
    std::vector<std::filesystem::path> model_files;
    std::error_code missing;
    for (const auto& entry : std::filesystem::directory_iterator(examples, missing))
      if (entry.path().extension() == ".toml") model_files.push_back(entry.path());
    std::sort(model_files.begin(), model_files.end());
    if (!model_files.empty()) {
      std::cout << "model files shipped with impactlab (give the path as the scene):\n";
      for (const auto& file : model_files)
        std::cout << fmt::format("  {}  {}\n", file.string(), scene_file_description(file));
    }
    return exit_done;
  }
  const Scene scene = load_scene(name);
  const SceneSchema& schema = scene_schema(scene);
  // "(read by model = ...)" after the keys that not every model reads
  std::string read_by_header;
  if (!schema.selector.empty()) {
    const auto selector = std::find_if(schema.keys.begin(), schema.keys.end(),
                                       [&](const KeySpec& k) { return k.key == schema.selector; });
    read_by_header = fmt::format(" (read by {} = ...; unmarked: {})", schema.selector,
                                 model_names(models_reading(schema, *selector)));
  }
  std::cout << fmt::format("{} ({}): key = value [unit] range: help{}\n", name, scene.oscillator,
                           read_by_header);
  for (const auto& spec : schema.keys) {
    const std::string value = to_text(scene.values.at(std::string(spec.key)));
    std::string range;
    if (spec.is_text) {
      for (auto choice : spec.choices) range += (range.empty() ? "" : "|") + std::string(choice);
    } else {
      range = range_text(spec);
    }
    const std::string read_by =
        spec.read_by.empty()
            ? ""
            : fmt::format(" (read by {} = {})", schema.selector, model_names(spec.read_by));
    std::cout << fmt::format("  {:<20} = {:<12} {:<10} {:<14} {}{}\n", spec.key, value,
                             spec.unit.empty() ? "" : "[" + std::string(spec.unit) + "]", range,
                             spec.help, read_by);
  }
  return exit_done;
}

}  // namespace

Command add_scenes_command(CLI::App& app) {
  auto* command = add_subcommand(app, "scenes", "list the built-in scenes, or one scene's keys");
  auto name = std::make_shared<std::string>();
  add_positional(*command, "scene", *name, "a scene whose keys, values, units and ranges to list");
  return {command, [name](const std::vector<std::string>&) { return run_scenes(*name); }};
}

}  // namespace impactlab::cli
