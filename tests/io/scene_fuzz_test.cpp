// Bounded randomized (fuzz) tests of the scene reader (io/scene.hpp) and of
// `--set`. Fixed seeds, so that a failure repeats.
//
// Inputs: the built-in scene files, mutated line by line (a value replaced by
// NaN, ±inf, 1e308, 1e-308, 1e400, an empty or long string, garbage, a
// boolean, an array, an inline table, a date; a line duplicated (a duplicated
// key) or deleted; a key renamed; random bytes inserted; the text cut short; a
// nested table added), and random KEY=VALUE pairs over every key of every
// oscillator with the same hostile values.
//
// The promise checked:
// * in the library: reading a scene or applying --set either succeeds or
//   throws BadInput whose message names its key, a key the file holds (or
//   `scene`, `oscillator`) or the key --set assigns; no other exception;
// * through the program: exit status 0, 2 or 3 only, never a signal or a hang;
//   on 2, one line under 200 characters naming a key the run sets or the file
//   holds, one a rule between keys names, or --periods (the run's length,
//   over limits.max_steps); on 0 and 3 a complete meta.json beside its data
//   and no NaN in events.csv; no temporary file left.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/builtin_scenes.hpp>
#include <impactlab/io/message_text.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/io/scene.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;
using namespace impactlab::testing;

// Values a scene file may hold, as TOML text.
const std::vector<std::string>& hostile_toml_values() {
  static const std::vector<std::string> values = {
      "nan", "inf", "-inf", "+nan", "1e308", "-1e308", "1e-308", "4.9e-324", "1e400", "0",
      "-0.0", "-1", "\"\"", "\"garbage\"", "garbage", "\"" + std::string(5000, 'x') + "\"",
      "true", "[1, 2]", "{ a = 1 }", "1979-05-27", "0x10", "1_000", "2.5", "\"1e308\"",
      "\"dopri5\"", "\"newton\"", "\"rigid\""};
  return values;
}

// Values given to --set, as the shell would pass them.
const std::vector<std::string>& hostile_set_values() {
  static const std::vector<std::string> values = {
      "nan", "NaN", "inf", "-inf", "infinity", "1e308", "-1e308", "1e-308", "-1e-308",
      "4.9e-324", "1e400", "0", "-0", "-1", "", " ", "garbage", "1,5", "0x1p3", "1e",
      std::string(100000, '9'), "1\n2", "\t3", "0.5", "2", "100", "1e6", "rigid", "paper",
      "newton", "exact", "rk8pd", "bulirsch_stoer"};
  return values;
}

std::string mutate(std::string_view scene_text, std::mt19937_64& rng) {
  std::vector<std::string> lines = split_lines(scene_text);
  auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  const int mutations = 1 + static_cast<int>(pick(3));
  for (int m = 0; m < mutations && !lines.empty(); ++m) {
    const std::size_t line = pick(lines.size());
    switch (pick(8)) {
      case 0:
      case 1: {  // a value replaced
        const auto equals = lines[line].find('=');
        if (equals != std::string::npos)
          lines[line] = lines[line].substr(0, equals + 1) + " " +
                        hostile_toml_values()[pick(hostile_toml_values().size())];
        break;
      }
      case 2: lines.insert(lines.begin() + static_cast<long>(line), lines[line]); break;
      case 3: lines.erase(lines.begin() + static_cast<long>(line)); break;
      case 4: {  // a key renamed
        const auto equals = lines[line].find('=');
        if (equals != std::string::npos)
          lines[line] = "k" + std::to_string(pick(1000)) + " " + lines[line].substr(equals);
        break;
      }
      case 5: {  // random bytes
        std::string bytes;
        for (std::size_t k = 0, n = 1 + pick(8); k < n; ++k)
          bytes += static_cast<char>(pick(256));
        lines[line].insert(pick(lines[line].size() + 1), bytes);
        break;
      }
      case 6: lines.insert(lines.begin() + static_cast<long>(line), "[initial.deeper]\nx = 1"); break;
      default: lines.resize(line); break;  // cut short
    }
  }
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  return text;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// Whether a refusal of the scene file `text` names a key it holds: `scene`
// (the file as a whole: it does not parse), `oscillator` (missing or
// unknown), or a key written in the text, each part of a dotted key (its
// table and its name) standing there.
bool names_a_key_of_the_text(const std::string& key, const std::string& text) {
  if (key == "scene" || key == "oscillator") return true;
  std::stringstream parts(key);
  for (std::string part; std::getline(parts, part, '.');)
    if (part.empty() || text.find(part) == std::string::npos) return false;
  return true;
}

// The keys a rule between keys names when it refuses a scene (the scene
// API's bindings): b < l, radius < b, spin = free needs a radius, a start
// inside a wall, no exact flow for the pendulum, the linear impact
// oscillator's exact flow only for ζ < 1.
const std::set<std::string> rule_keys = {"b",         "radius",    "spin",
                                         "initial.theta", "integrator.method", "zeta",
                                         "initial.x", "initial.y"};

// The library's side: a scene either reads or throws BadInput naming its key.
TEST(SceneFuzz, MutatedBuiltinScenesReadOrThrowBadInputNamingTheKey) {
  const ScratchFolder dir;
  std::mt19937_64 rng(13);
  int accepted = 0, refused = 0;
  constexpr int per_scene = 400;
  for (const auto& builtin : builtin_scenes()) {
    for (int k = 0; k < per_scene; ++k) {
      const std::string text = mutate(builtin.text, rng);
      const auto path = dir / "mutated.toml";
      write_text(path, text);
      try {
        const Scene scene = load_scene(path.string());
        ++accepted;
        EXPECT_FALSE(scene.oscillator.empty());
      } catch (const BadInput& bad) {
        ++refused;
        EXPECT_TRUE(names_a_key_of_the_text(bad.key(), text)) << bad.what() << " for scene:\n"
                                                               << text;
        const std::string message = one_line(bad.what());
        EXPECT_LE(message.size(), message_limit);
        EXPECT_EQ(message.find('\n'), std::string::npos);
        EXPECT_NE(message.find(elide_value(bad.key())), std::string::npos) << message;
      } catch (const std::exception& error) {
        ADD_FAILURE() << "unexpected exception " << error.what() << " for scene:\n" << text;
      }
    }
  }
  // the mutations reach both sides of the reader
  EXPECT_GT(accepted, 50);
  EXPECT_GT(refused, 50);
  std::cout << "[ fuzz     ] scene files: " << accepted + refused << " inputs, " << accepted
            << " accepted, " << refused << " refused\n";
}

TEST(SceneFuzz, RandomSetAssignmentsApplyOrThrowBadInputNamingTheKey) {
  std::mt19937_64 rng(1313);
  int accepted = 0, refused = 0;
  for (const auto& entry : oscillators()) {
    const auto& keys = entry.schema->keys;
    std::string scene_name;
    for (const auto& builtin : builtin_scenes())
      if (load_scene(builtin.name).oscillator == entry.schema->oscillator) scene_name = builtin.name;
    ASSERT_FALSE(scene_name.empty());
    for (int k = 0; k < 1500; ++k) {
      Scene scene = load_scene(scene_name);
      const auto& spec = keys[std::uniform_int_distribution<std::size_t>(0, keys.size() - 1)(rng)];
      const auto& value = hostile_set_values()[std::uniform_int_distribution<std::size_t>(
          0, hostile_set_values().size() - 1)(rng)];
      const std::string key =
          rng() % 10 == 0 ? std::string(spec.key) + "x" : std::string(spec.key);
      try {
        apply_override(scene, key + "=" + value);
        ++accepted;
        for (const auto& [name, stored] : scene.values) {
          if (const auto* number = std::get_if<double>(&stored)) {
            EXPECT_TRUE(std::isfinite(*number)) << name;
          }
        }
      } catch (const BadInput& bad) {
        ++refused;
        // the key assigned, whatever its value
        EXPECT_EQ(bad.key(), key) << bad.what();
        EXPECT_NE(one_line(bad.what()).find(elide_value(bad.key())), std::string::npos);
      } catch (const std::exception& error) {
        ADD_FAILURE() << "unexpected exception " << error.what() << " for --set " << key;
      }
    }
  }
  EXPECT_GT(accepted, 100);
  EXPECT_GT(refused, 100);
  std::cout << "[ fuzz     ] --set: " << accepted + refused << " inputs, " << accepted
            << " accepted, " << refused << " refused\n";
}

// Every file in `out` is a finished output: no temporary left, and a
// meta.json that parses; no NaN in events.csv.
void expect_complete_outputs(const std::filesystem::path& out, const std::string& context) {
  if (!std::filesystem::exists(out)) return;
  for (const auto& file : std::filesystem::directory_iterator(out)) {
    const std::string name = file.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << context << ": " << name;
  }
  if (std::filesystem::exists(out / "events.csv")) {
    EXPECT_TRUE(std::filesystem::exists(out / "meta.json")) << context;
    // t, q, qdot_before, qdot_after of every row: present and finite (the
    // writer leaves a NaN field empty)
    const std::vector<std::string> rows = split_lines(slurp(out / "events.csv"));
    for (std::size_t row = 1; row < rows.size(); ++row) {
      std::vector<std::string> fields;
      std::stringstream line(rows[row]);
      for (std::string field; std::getline(line, field, ',');) fields.push_back(field);
      ASSERT_GE(fields.size(), 6u) << context << ": " << rows[row];
      for (const std::size_t column : {0u, 3u, 4u, 5u}) {
        char* end = nullptr;
        const double value = std::strtod(fields[column].c_str(), &end);
        EXPECT_TRUE(!fields[column].empty() && *end == '\0' && std::isfinite(value))
            << context << ": events.csv row " << row << ": " << rows[row];
      }
    }
  }
  if (std::filesystem::exists(out / "meta.json")) {
    EXPECT_TRUE(nlohmann::json::accept(slurp(out / "meta.json"))) << context;
  }
}

// The subject of the program's one line of bad input: KEY in "impactlab: KEY
// = VALUE: reason" or "impactlab: KEY: reason".
std::string subject_of(const std::string& line) {
  const std::string message = line.substr(line.find(": ") + 2);
  return message.substr(0, message.find_first_of(" :"));
}

// The program's promise for one run; `expected_subject(KEY)` says whether a
// refusal (exit 2) may name KEY.
template <class ExpectedSubject>
void expect_promise(const ProgramRun& run, const std::filesystem::path& out,
                    const std::string& context, ExpectedSubject expected_subject) {
  EXPECT_FALSE(run.timed_out) << context;
  EXPECT_EQ(run.signal, 0) << context;
  EXPECT_TRUE(run.status == 0 || run.status == 2 || run.status == 3)
      << context << ": exit " << run.status << ": " << run.err;
  if (run.status == 2) {
    EXPECT_EQ(count_lines(run.err), 1) << context << ": " << run.err;
    EXPECT_LT(run.err.size(), 200u) << context;
    EXPECT_NE(run.err.find(" = "), std::string::npos) << context << ": " << run.err;
    EXPECT_TRUE(expected_subject(subject_of(run.err))) << context << ": " << run.err;
    // nothing written by a refused run
    if (std::filesystem::exists(out)) {
      EXPECT_TRUE(std::filesystem::is_empty(out)) << context;
    }
  } else if (run.status == 0 || run.status == 3) {
    EXPECT_TRUE(std::filesystem::exists(out / "meta.json")) << context << ": " << run.err;
  }
  expect_complete_outputs(out, context);
}

// Through the program: random --set pairs on short runs. The step budget is
// set last (after the fuzzed pairs) so that each run stays short.
TEST(SceneFuzz, ProgramKeepsItsPromiseOnRandomSetPairs) {
  const ScratchFolder dir;
  std::mt19937_64 rng(131313);
  const std::vector<std::string> scenes = {"jin2003", "bouncing_ball", "linear_impact"};
  int runs = 0;
  for (int k = 0; k < 120; ++k) {
    const std::string& scene = scenes[static_cast<std::size_t>(k) % scenes.size()];
    const auto& keys = oscillator_entry(load_scene(scene).oscillator).schema->keys;
    std::vector<std::string> arguments = {"simulate", scene, "--periods", "0.5", "--quiet",
                                          "--out", "o" + std::to_string(k)};
    for (int pair = 0; pair < 2; ++pair) {
      const auto& spec = keys[std::uniform_int_distribution<std::size_t>(0, keys.size() - 1)(rng)];
      const auto& value = hostile_set_values()[std::uniform_int_distribution<std::size_t>(
          0, hostile_set_values().size() - 1)(rng)];
      arguments.insert(arguments.end(), {"--set", std::string(spec.key) + "=" + value});
    }
    arguments.insert(arguments.end(), {"--set", "limits.max_steps=200000"});
    const ProgramRun run = run_impactlab(arguments, {.directory = dir.path(), .limit_s = 60});
    // refused for a key it sets, a rule between keys, or the length of the
    // run (--periods, against limits.max_steps)
    const std::set<std::string> set_keys = {arguments[8].substr(0, arguments[8].find('=')),
                                            arguments[10].substr(0, arguments[10].find('=')),
                                            "limits.max_steps"};
    expect_promise(run, dir / ("o" + std::to_string(k)),
                   arguments[1] + " " + arguments[8] + " " + arguments[10],
                   [&](const std::string& subject) {
                     return set_keys.contains(subject) || rule_keys.contains(subject) ||
                            subject == "--periods";
                   });
    ++runs;
  }
  std::cout << "[ fuzz     ] program --set: " << runs << " runs\n";
}

// Through the program: mutated scene files, short runs.
TEST(SceneFuzz, ProgramKeepsItsPromiseOnMutatedSceneFiles) {
  const ScratchFolder dir;
  std::mt19937_64 rng(1313131);
  int runs = 0;
  for (const auto& builtin : builtin_scenes()) {
    for (int k = 0; k < 30; ++k) {
      const std::string name = std::string(builtin.name) + std::to_string(k);
      const std::string text = mutate(builtin.text, rng);
      write_text(dir / (name + ".toml"), text);
      const ProgramRun run = run_impactlab({"simulate", name + ".toml", "--periods", "0.5",
                                            "--quiet", "--out", "o" + name, "--set",
                                            "limits.max_steps=200000"},
                                           {.directory = dir.path(), .limit_s = 60});
      // refused for a key of the file, a rule between keys, or the length
      // of the run (--periods, against limits.max_steps)
      expect_promise(run, dir / ("o" + name), name + ".toml", [&](const std::string& subject) {
        return names_a_key_of_the_text(subject, text) || rule_keys.contains(subject) ||
               subject == "--periods" || subject == "limits.max_steps";
      });
      ++runs;
    }
  }
  std::cout << "[ fuzz     ] program scene files: " << runs << " runs\n";
}

}  // namespace
