// `impactlab sweep`: 1D bifurcation sweeps (bifurcation.csv, summary.csv) and
// 2D classification maps (classes.csv) over any numeric scene parameter, and
// `impactlab basins`: a 2D sweep whose points each start from the scene's
// state with the two keys set (basins.csv, attractors.csv; the attractors
// told apart by analysis/basins.hpp), on
// threads (--threads) and, under mpirun, across MPI ranks; resumable from a
// per-rank checkpoint (checkpoint-<rank>.jsonl, one flushed line per point,
// first line identifying the sweep). The data files and meta.json appear only
// when the whole sweep is complete, written by rank 0 (AtomicFile).
#include <algorithm>
#include <atomic>
#include <exception>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>

#include <fmt/format.h>
#include <omp.h>

#include "analysis/basins.hpp"
#include "analysis/sweep.hpp"
#include "api/scene_jobs.hpp"
#include "cli/command.hpp"
#include "cli/commands.hpp"
#include "cli/mpi_session.hpp"
#include "cli/section_options.hpp"
#include "io/bad_input.hpp"
#include "io/output.hpp"

namespace impactlab::cli {

namespace {

struct SweepOptions {
  SectionOptions section;
  std::vector<std::string> params;
  std::string direction = "up";
  int threads = 1;
  int chunks = 1;
  bool lyapunov = false, no_lyapunov = false;
  bool resume = false;
  long stop_after = 0;  // hidden, for tests: stop after this many new points per rank
  double period_tolerance = 1e-6;
  int max_period = 16;
  bool basins = false;             // `impactlab basins`: params are --x, --y
  double attractor_tolerance = 1e-4;  // basins: relative distance of canonical points
};

std::string number(double value) { return fmt::format("{}", value); }

using RecordKey = std::pair<int, int>;  // task, position

std::string checkpoint_name(int rank) { return fmt::format("checkpoint-{}.jsonl", rank); }

// finished points from every checkpoint file in `directory` whose first line is `header`
std::map<RecordKey, SweepRecord> read_checkpoints(const std::filesystem::path& directory,
                                                  const std::string& header) {
  std::map<RecordKey, SweepRecord> done;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("checkpoint-") || !name.ends_with(".jsonl")) continue;
    std::ifstream in(entry.path());
    std::string line;
    if (!std::getline(in, line) || line != header) continue;
    while (std::getline(in, line))
      if (auto record = from_json_line(line))
        done.emplace(RecordKey{record->task, record->position}, std::move(*record));
  }
  return done;
}

std::string csv_bool(bool value) { return value ? "1" : "0"; }

// basins.csv (each grid point's attractor) and attractors.csv (each
// attractor's class, canonical section point and basin size)
void write_basins(RunFiles& run_files, const SweepPlan& plan, const std::vector<SweepTask>& tasks,
                  const std::map<RecordKey, SweepRecord>& records, std::vector<std::string>& files) {
  std::vector<const SweepRecord*> in_grid_order;
  for (const auto& task : tasks)
    for (std::size_t p = 0; p < task.points.size(); ++p)
      in_grid_order.push_back(&records.at({task.id, static_cast<int>(p)}));
  const BasinMap map = identify_attractors(in_grid_order, plan.attractor_tolerance);
  AtomicFile& basins = run_files.add("basins.csv");
  basins.stream() << plan.axes[0].name << ',' << plan.axes[1].name
                  << ",attractor,period,impacts_per_period,contact,termination\n";
  for (std::size_t k = 0; k < in_grid_order.size(); ++k) {
    const SweepRecord& r = *in_grid_order[k];
    basins.stream() << number(plan.axes[0].value(r.index[0])) << ','
                    << number(plan.axes[1].value(r.index[1])) << ',' << map.attractor[k] << ','
                    << r.classification.period << ','
                    << number(r.classification.impacts_per_period) << ','
                    << csv_bool(r.classification.contact) << ',' << r.result.termination << '\n';
  }
  AtomicFile& attractors = run_files.add("attractors.csv");
  attractors.stream() << "attractor,period,impacts_per_period,contact,q,qdot,basin_points\n";
  if (map.unclassified > 0)
    attractors.stream() << "0,0,nan,0,nan,nan," << map.unclassified << '\n';
  for (const Attractor& a : map.attractors)
    attractors.stream() << a.id << ',' << a.period << ',' << number(a.impacts_per_period) << ','
                        << csv_bool(a.contact) << ',' << number(a.point[0]) << ','
                        << number(a.point[1]) << ',' << a.basin_points << '\n';
  files = {"basins.csv", "attractors.csv"};
}

void write_outputs(RunFiles& run_files, const SweepPlan& plan,
                   const std::vector<SweepTask>& tasks,
                   const std::map<RecordKey, SweepRecord>& records, std::vector<std::string>& files) {
  auto summary_fields = [](const SweepRecord& r) {
    return fmt::format("{},{},{},{},{}", r.classification.period,
                       number(r.classification.impacts_per_period),
                       csv_bool(r.classification.contact), number(r.result.lyapunov),
                       r.result.termination);
  };
  if (plan.axes.size() == 2 && !plan.follow_attractor) {
    write_basins(run_files, plan, tasks, records, files);
    return;
  }
  if (plan.axes.size() == 1) {
    const SweepAxis& axis = plan.axes[0];
    AtomicFile& bifurcation = run_files.add("bifurcation.csv");
    AtomicFile& summary = run_files.add("summary.csv");
    bifurcation.stream() << axis.name << ",k,t,q,qdot,wall,direction\n";
    summary.stream() << axis.name
                     << ",direction,period,impacts_per_period,contact,lyapunov,termination,"
                        "points\n";
    for (int direction : {1, -1}) {
      // this direction's records by grid index, written in the sweep's order
      std::map<int, const SweepRecord*> by_index;
      for (const auto& task : tasks)
        if (task.direction == direction)
          for (std::size_t p = 0; p < task.points.size(); ++p)
            by_index[task.points[p][0]] = &records.at({task.id, static_cast<int>(p)});
      if (by_index.empty()) continue;
      const std::string name = direction > 0 ? "up" : "down";
      auto write = [&](const SweepRecord& r) {
        const std::string value = number(axis.value(r.index[0]));
        for (std::size_t k = 0; k < r.result.points.size(); ++k) {
          const SectionPoint& p = r.result.points[k];
          bifurcation.stream() << value << ',' << k << ',' << number(p.t) << ',' << number(p.q)
                               << ',' << number(p.qdot) << ',' << p.wall << ',' << name << '\n';
        }
        summary.stream() << value << ',' << name << ',' << summary_fields(r) << ','
                         << r.result.points.size() << '\n';
      };
      if (direction > 0)
        for (const auto& [index, record] : by_index) write(*record);
      else
        for (auto it = by_index.rbegin(); it != by_index.rend(); ++it) write(*it->second);
    }
    files = {"bifurcation.csv", "summary.csv"};
    return;
  }
  AtomicFile& classes = run_files.add("classes.csv");
  classes.stream() << plan.axes[0].name << ',' << plan.axes[1].name
                   << ",period,impacts_per_period,contact,lyapunov,termination\n";
  for (const auto& task : tasks)
    for (std::size_t p = 0; p < task.points.size(); ++p) {
      const SweepRecord& r = records.at({task.id, static_cast<int>(p)});
      classes.stream() << number(plan.axes[0].value(r.index[0])) << ','
                       << number(plan.axes[1].value(r.index[1])) << ',' << summary_fields(r)
                       << '\n';
    }
  files = {"classes.csv"};
}

// The plan the options describe, validated against the scene (BadInput).
SweepPlan plan_from(const SweepOptions& options, const Scene& scene, const SceneSchema& schema) {
  SweepPlan plan;
  if (options.basins) {
    plan.axes = {parse_axis(options.params.at(0), "--x"), parse_axis(options.params.at(1), "--y")};
    plan.follow_attractor = false;
    plan.attractor_tolerance = options.attractor_tolerance;
    if (plan.axes[0].name == plan.axes[1].name)
      throw BadInput("--y", plan.axes[1].name, "must differ from --x's key");
    // the keys named by the options that gave them (validate_plan says --param)
    for (const auto& [option, axis] : {std::pair{"--x", plan.axes[0]}, std::pair{"--y", plan.axes[1]}}) {
      const auto spec = std::find_if(schema.keys.begin(), schema.keys.end(),
                                     [&](const KeySpec& k) { return k.key == axis.name; });
      if (spec == schema.keys.end() || spec->is_text)
        throw BadInput(option, axis.name,
                       fmt::format("not a numeric key of oscillator {}", schema.oscillator));
    }
  } else {
    for (const auto& text : options.params) plan.axes.push_back(parse_axis(text, "--param"));
  }
  plan.direction = parse_direction(options.direction, "--direction");
  plan.chunks = options.chunks;
  plan.section = options.section.request();
  plan.period_tolerance = options.period_tolerance;
  plan.max_period = options.max_period;
  // Lyapunov: on by default for 2D maps, off for 1D sweeps
  plan.section.lyapunov =
      options.lyapunov || (plan.axes.size() == 2 && !options.no_lyapunov && !options.basins);
  validate_plan(plan, scene, schema);
  if (plan.axes.size() == 2 && plan.direction != SweepDirection::up)
    throw BadInput("--direction", options.direction,
                   "a 2D sweep follows the first parameter upwards only");
  return plan;
}

// Everything that decides the sweep's results (and nothing that does not,
// such as threads or ranks): the checkpoint header and meta.json's "sweep".
nlohmann::json sweep_definition(const SweepOptions& options, const SweepPlan& plan,
                                const Scene& scene, const SceneSchema& schema) {
  nlohmann::json axes = nlohmann::json::array();
  for (const auto& a : plan.axes) {
    const auto spec = std::find_if(schema.keys.begin(), schema.keys.end(),
                                   [&](const KeySpec& k) { return k.key == a.name; });
    axes.push_back({{"name", a.name},
                    {"unit", std::string(spec->unit)},
                    {"from", a.from},
                    {"to", a.to},
                    {"count", a.count}});
  }
  nlohmann::json definition = {
      {"scene", scene_record(scene)},
      {"axes", axes},
      {"direction", to_string(plan.direction)},
      {"chunks", plan.chunks},
      {"section", options.section.record()},
      {"lyapunov", plan.section.lyapunov},
      {"lyapunov_alignment_periods", plan.section.lyapunov_alignment_periods},
      {"period_tolerance", plan.period_tolerance},
      {"max_period", plan.max_period},
      {"impactlab_version", IMPACTLAB_VERSION},
  };
  if (options.basins) {
    definition["basins"] = true;  // every point from the scene's state
    definition["attractor_tolerance"] = plan.attractor_tolerance;
  }
  return definition;
}

// This rank's checkpoint, opened for appending; one that is not this
// sweep's (or any, without --resume) is started afresh with the header.
std::ofstream open_checkpoint(const std::filesystem::path& path, const std::string& header,
                              bool resume) {
  {
    std::ifstream existing(path);
    std::string first;
    const bool keep = resume && std::getline(existing, first) && first == header;
    if (!keep) std::ofstream(path, std::ios::trunc) << header << '\n';
  }
  std::ofstream checkpoint(path, std::ios::app);
  if (!checkpoint) throw BadInput("--out", path.parent_path().string(), "cannot write the checkpoint");
  return checkpoint;
}

struct RankWork {
  std::vector<std::vector<SweepRecord>> records;  // per task of this rank, in order
  bool stopped = false;                           // --stop-after ended it early
};

// Runs this rank's tasks on `threads` threads: finished points are taken from
// `done`, new ones appended to the checkpoint as they finish.
RankWork run_rank_tasks(const Scene& scene, const SweepTarget& target, const SweepPlan& plan,
                        const std::vector<const SweepTask*>& tasks,
                        const std::map<RecordKey, SweepRecord>& done, std::ofstream& checkpoint,
                        const SweepOptions& options, bool show_progress) {
  std::size_t points = 0;
  for (const SweepTask* task : tasks) points += task->points.size();
  ProgressBar progress(show_progress);
  std::mutex mutex;  // guards the checkpoint, the progress bar and `failure`
  std::size_t finished = 0;
  std::atomic<long> new_points{0};
  std::atomic<bool> stopped{false};
  std::exception_ptr failure;
  RankWork work;
  work.records.resize(tasks.size());
  auto advance_progress = [&] {
    progress.update(static_cast<double>(++finished) / static_cast<double>(points));
  };

#pragma omp parallel for schedule(dynamic, 1) num_threads(options.threads)
  for (std::size_t m = 0; m < tasks.size(); ++m) {
    try {
      const SweepTask& task = *tasks[m];
      work.records[m] = run_sweep_task(
          scene, target, plan, task,
          [&](int position) -> const SweepRecord* {
            const auto it = done.find({task.id, position});
            if (it == done.end()) return nullptr;
            std::lock_guard lock(mutex);
            advance_progress();
            return &it->second;
          },
          [&](const SweepRecord& record) {
            const std::string line = to_json_line(record);
            std::lock_guard lock(mutex);
            checkpoint << line << '\n' << std::flush;
            advance_progress();
          },
          [&] {
            if (stopped) return false;
            if (options.stop_after > 0 && new_points.fetch_add(1) >= options.stop_after) {
              stopped = true;
              return false;
            }
            return true;
          });
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!failure) failure = std::current_exception();
      stopped = true;
    }
  }
  if (failure) std::rethrow_exception(failure);
  work.stopped = stopped;
  return work;
}

// The records in every rank's text (one checkpoint line each), by key.
std::map<RecordKey, SweepRecord> parse_records(const std::vector<std::string>& texts) {
  std::map<RecordKey, SweepRecord> all;
  for (const auto& text : texts) {
    std::size_t begin = 0;
    while (begin < text.size()) {
      const std::size_t end = text.find('\n', begin);
      if (auto record = from_json_line(std::string_view(text).substr(begin, end - begin)))
        all.emplace(RecordKey{record->task, record->position}, std::move(*record));
      begin = end == std::string::npos ? text.size() : end + 1;
    }
  }
  return all;
}

void write_meta(RunFiles& run_files, const nlohmann::json& definition,
                const Scene& scene, const SceneSchema& schema,
                const std::map<RecordKey, SweepRecord>& all, nlohmann::json run,
                const std::vector<std::string>& command_line, std::vector<std::string> files) {
  std::uint64_t steps = 0, rhs = 0, stopped_points = 0;
  for (const auto& [key, record] : all) {
    steps += record.result.steps;
    rhs += record.result.rhs_evaluations;
    if (record.result.termination != "completed") ++stopped_points;
  }
  files.push_back("meta.json");
  const std::string q_name(schema.main_coordinate);
  const nlohmann::json meta = {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"command", command_line},
      {"created_utc", utc_now()},
      {"sweep", definition},
      {"scene", scene_record(scene)},
      {"run", std::move(run)},
      {"counts",
       {{"points", all.size()},
        {"points_stopped_early", stopped_points},
        {"steps", steps},
        {"rhs_evaluations", rhs}}},
      {"columns",
       {{"k", "index of the section point at this parameter value"},
        {"t", "time of the section point (scene time unit)"},
        {"q", q_name},
        {"qdot", "d" + q_name + "/dt (before the impact, for the impact map)"},
        {"wall", "impact map: wall hit (+1 / -1); 0 for stroboscopic points"},
        {"direction", "up / down: the continuation direction"},
        {"period", "smallest p with section point k+p within period_tolerance of point k "
                   "(relative to 1 + |(q, qdot)|); 0: none up to max_period"},
        {"impacts_per_period", "impacts per forcing period in the record window"},
        {"contact", "1 if a contact (sticking/sliding) phase began or ended in the record window"},
        {"lyapunov", "largest Lyapunov exponent (1/time unit); nan where not computed, -inf "
                     "where nearby states merge (rest on a wall)"},
        {"termination", "completed, stopped_by_model, no_progress, ..."},
        {"points", "section points recorded"},
        {"attractor", "basins: the attractor the point settles on (attractors.csv; 0: none found)"},
        {"basin_points", "basins: grid points that settle on the attractor"}}},
      {"files", files},
  };
  write_json(run_files.add("meta.json"), meta);
}

int run_sweep(const SweepOptions& options, const std::vector<std::string>& command_line) {
  const Scene scene = options.section.scene.load();
  const SweepTarget target = sweep_target(scene);
  const SweepPlan plan = plan_from(options, scene, *target.schema);
  const auto directory = options.section.scene.output_directory();
  // the sweep's data files and meta.json, committed together by rank 0
  RunFiles run_files(directory);
  // MPI starts once the input is known to be good: bad input exits with
  // status 2 on every rank alike, before any rank waits for another
  MpiSession mpi;

  const nlohmann::json definition = sweep_definition(options, plan, scene, *target.schema);
  const std::string header = nlohmann::json{{"impactlab_sweep_checkpoint", definition}}.dump();
  std::map<RecordKey, SweepRecord> done;
  if (options.resume) done = read_checkpoints(directory, header);
  std::ofstream checkpoint =
      open_checkpoint(directory / checkpoint_name(mpi.rank()), header, options.resume);

  // this rank's share: task id mod ranks
  const std::vector<SweepTask> tasks = sweep_tasks(plan);
  std::vector<const SweepTask*> mine;
  std::size_t total_points = 0;
  for (const auto& task : tasks) {
    total_points += task.points.size();
    if (task.id % mpi.size() == mpi.rank()) mine.push_back(&task);
  }
  const auto start = std::chrono::steady_clock::now();
  const RankWork work = run_rank_tasks(scene, target, plan, mine, done, checkpoint, options,
                                       !options.section.scene.quiet && mpi.rank() == 0);
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // every rank's records to rank 0, which writes
  std::string text;
  for (const auto& records : work.records)
    for (const auto& record : records) text += to_json_line(record) + '\n';
  const std::vector<std::string> gathered = mpi.gather(text);
  if (mpi.rank() != 0) return work.stopped ? exit_stopped_early : exit_done;
  const std::map<RecordKey, SweepRecord> all = parse_records(gathered);
  if (all.size() < total_points) {
    std::cerr << fmt::format(
        "impactlab: sweep stopped after {} of {} points (checkpoint in {}); run again with "
        "--resume to finish it\n",
        all.size(), total_points, directory.string());
    return exit_stopped_early;
  }

  std::vector<std::string> files;
  write_outputs(run_files, plan, tasks, all, files);
  write_meta(run_files, definition, scene, *target.schema, all,
             {{"threads", options.threads},
              {"mpi_ranks", mpi.size()},
              {"tasks", tasks.size()},
              {"points_reused_from_checkpoint", done.size()},
              {"wall_time_s", wall_time}},
             command_line, files);
  run_files.commit();
  // the sweep is complete: its checkpoints (of any rank count) are spent
  for (const auto& file : std::filesystem::directory_iterator(directory)) {
    const std::string name = file.path().filename().string();
    if (name.starts_with("checkpoint-") && name.ends_with(".jsonl"))
      std::filesystem::remove(file.path());
  }

  const std::string q_name(target.schema->main_coordinate);
  if (options.section.plot) {
    if (options.basins)
      plot_with_python("basins", directory / "basins.csv", directory / "basins.png",
                       {plan.axes[0].name, plan.axes[1].name});
    else if (plan.axes.size() == 1)
      plot_with_python("bifurcation", directory / "bifurcation.csv",
                       directory / "bifurcation.png", {plan.axes[0].name, q_name});
    else
      plot_with_python("classes", directory / "classes.csv", directory / "classes.png",
                       {plan.axes[0].name, plan.axes[1].name});
  }
  if (!options.section.scene.quiet)
    std::cout << fmt::format("{}: {} points ({} reused), {} threads x {} ranks, {:.3f} s wall\n"
                             "wrote {}\n",
                             scene.name, all.size(), done.size(), options.threads, mpi.size(),
                             wall_time, (directory / files.front()).string());
  return exit_done;
}

}  // namespace

Command add_sweep_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "sweep",
      "1D bifurcation sweep (bifurcation.csv, summary.csv) or 2D classification map "
      "(classes.csv) over scene parameters");
  auto options = std::make_shared<SweepOptions>();
  options->section.add_to(*command,
                          "section points recorded per value (strobe: forcing periods; "
                          "impact: impacts)");
  command->add_option("--param", options->params,
                      "NAME=FROM:TO:N, once (1D bifurcation sweep) or twice (2D map)")
      ->required()
      ->expected(1, 2);
  command->add_option("--direction", options->direction,
                      "1D: follow the attractor up, down or both ways")
      ->capture_default_str();
  command->add_option("--threads", options->threads, "worker threads")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  command->add_option("--chunks", options->chunks,
                      "1D: split each direction into this many continuation runs, each from "
                      "the scene's initial state (lets threads share a 1D sweep)")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  auto* lyapunov = command->add_flag(
      "--lyapunov", options->lyapunov,
      "compute the largest Lyapunov exponent (default: on for 2D, off for 1D)");
  command->add_flag("--no-lyapunov", options->no_lyapunov, "do not compute it in a 2D map")
      ->excludes(lyapunov);
  command->add_option("--period-tol", options->period_tolerance,
                      "relative distance under which section points count as repeating")
      ->check(positive_number())
      ->capture_default_str();
  command->add_option("--max-period", options->max_period, "longest period looked for")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  command->add_flag("--resume", options->resume,
                    "reuse the finished points of an interrupted run of the same sweep in --out");
  // for tests of --resume: stop (exit 3, checkpoint kept) after this many new points per rank
  command->add_option("--stop-after", options->stop_after)->group("")->check(CLI::Range(1L, 1L << 40));
  return {command, [options](const std::vector<std::string>& command_line) {
            return run_sweep(*options, command_line);
          }};
}

Command add_basins_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "basins",
      "basins of attraction: each initial condition of a 2D grid (e.g. initial.theta x "
      "initial.theta_dot) classified by the attractor it settles on (basins.csv, attractors.csv)");
  auto options = std::make_shared<SweepOptions>();
  options->basins = true;
  options->params.resize(2);
  options->section.add_to(*command,
                          "section points recorded per initial condition (strobe: forcing "
                          "periods; impact: impacts)");
  command->add_option("--x", options->params[0], "KEY=FROM:TO:N: the first grid key (fastest)")
      ->required();
  command->add_option("--y", options->params[1], "KEY=FROM:TO:N: the second grid key")->required();
  command->add_option("--threads", options->threads, "worker threads")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  command->add_flag("--lyapunov", options->lyapunov, "also compute the largest Lyapunov exponent");
  command->add_option("--period-tol", options->period_tolerance,
                      "relative distance under which section points count as repeating")
      ->check(positive_number())
      ->capture_default_str();
  command->add_option("--max-period", options->max_period, "longest period looked for")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  command->add_option("--attractor-tol", options->attractor_tolerance,
                      "relative distance under which two canonical section points are one "
                      "attractor")
      ->check(positive_number())
      ->capture_default_str();
  command->add_flag("--resume", options->resume,
                    "reuse the finished points of an interrupted run of the same map in --out");
  command->add_option("--stop-after", options->stop_after)->group("")->check(CLI::Range(1L, 1L << 40));
  return {command, [options](const std::vector<std::string>& command_line) {
            return run_sweep(*options, command_line);
          }};
}

}  // namespace impactlab::cli
