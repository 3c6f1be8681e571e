#include <impactlab/io/scene_file.hpp>

#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include <impactlab/io/output.hpp>
#include <impactlab/io/output_error.hpp>

namespace impactlab {

namespace {

// A TOML basic string: quotes, backslashes and control characters escaped.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      out += fmt::format("\\u{:04x}", static_cast<unsigned char>(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// A number that reads back as the same double: the shortest text that does
// (integral values as TOML integers, which the reader takes as numbers).
std::string number_text(double value) { return fmt::format("{}", value); }

constexpr std::string_view model_prefix = "model:";

}  // namespace

std::string scene_file_text(const Scene& scene, const SceneSchema& schema) {
  std::string text = fmt::format(
      "# The scene {} ({}), every key with its value: `impactlab ... FILE` runs it as it "
      "was.\n",
      scene.name, scene.oscillator);
  const bool model_file = scene.oscillator.starts_with(model_prefix);
  if (!model_file) text += fmt::format("oscillator = {}\n", quoted(scene.oscillator));
  for (const KeySpec& spec : schema.keys) {
    const auto value = scene.values.find(std::string(spec.key));
    if (value == scene.values.end()) continue;
    const auto* number = std::get_if<double>(&value->second);
    const std::string shown =
        number ? number_text(*number) : quoted(std::get<std::string>(value->second));
    const std::string unit = spec.unit.empty() ? "" : fmt::format("[{}] ", spec.unit);
    text += fmt::format("{} = {}  # {}{}\n", spec.key, shown, unit, spec.help);
  }
  if (model_file) {
    // the model the file defines, as that file states it
    const std::string path = scene.oscillator.substr(model_prefix.size());
    toml::table model;
    try {
      const toml::table file = toml::parse_file(path);
      if (const toml::node* section = file.get("model")) model.insert("model", *section);
    } catch (const toml::parse_error& error) {
      throw OutputError(fmt::format("{}: the scene's model file no longer reads: {}", path,
                                    error.description()));
    }
    std::ostringstream section;
    section << model;
    text += '\n';
    text += section.str();
    text += '\n';
  }
  return text;
}

void save_scene_file(const Scene& scene, const SceneSchema& schema,
                     const std::filesystem::path& path) {
  AtomicFile file(path);
  file.stream() << scene_file_text(scene, schema);
  file.commit();
}

}  // namespace impactlab
