// `impactlab sweep`: 1D bifurcation sweeps (bifurcation.csv, summary.csv) and
// 2D classification maps (classes.csv) over any numeric scene parameter,
// `impactlab basins`: a 2D sweep whose points each start from the scene's
// state with the two keys set (basins.csv, attractors.csv; the attractors
// told apart by analysis/basins.hpp), and `impactlab attractors`: samples of
// initial states at each value of one parameter, their attractors followed
// along it (attractors.csv, attractor_points.csv, samples.csv;
// analysis/attractor_following.hpp), on
// threads (--threads) and, under mpirun, across MPI ranks; resumable from a
// per-rank checkpoint (checkpoint-<rank>.jsonl, one flushed line per point,
// first line identifying the sweep). The data files and meta.json appear only
// when the whole sweep is complete, written by rank 0 (AtomicFile).
#include <algorithm>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <optional>

#include <fmt/format.h>

#include <impactlab/analysis/sweep.hpp>
#include <impactlab/api/attractors_job.hpp>
#include <impactlab/api/basins_job.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/section_record.hpp>
#include <impactlab/api/sweep_checkpoints.hpp>
#include <impactlab/api/sweep_job.hpp>
#include "command.hpp"
#include "interrupted_runs.hpp"
#include "commands.hpp"
#include "mpi_session.hpp"
#include "section_options.hpp"
#include "table_options.hpp"
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/output.hpp>
#include <impactlab/io/output_error.hpp>

namespace impactlab::cli {

namespace {

// The values as given; their defaults come from the "sweep", "basins" or
// "attractors" option table.
struct SweepOptions {
  SectionOptions section;
  std::vector<std::string> params;
  std::string direction;
  int threads = 0;
  std::string batch;  // on | off (api/sweep_job.hpp)
  int chunks = 0;
  bool lyapunov = false, no_lyapunov = false;
  bool lyapunov_spectrum = false;  // also all N exponents (columns lyapunov1..N)
  bool resume = false;
  long stop_after = 0;  // hidden, for tests: stop after this many new points per rank
  double period_tolerance = 0.0;
  int max_period = 0;
  std::string classification_tolerance;  // auto | off (api/sweep_job.hpp)
  bool basins = false;                 // `impactlab basins`: params are --x, --y
  double attractor_tolerance = 0.0;    // basins: relative distance of canonical points
  int entropy_box = 0;  // basins: box side of the basin entropies (grid points); 0: not given
  bool attractors = false;        // `impactlab attractors`: params holds --param alone
  int samples = 0;                // attractors: initial states per value
  std::vector<std::string> box;   // attractors: KEY=FROM:TO each
  std::uint64_t seed = 0;         // attractors: seed of the samples
  double match_tolerance = 0.0;   // attractors: relative distance of point sets
};

std::string number(double value) { return fmt::format("{}", value); }

using RecordKey = SweepRecordKey;

// the spectrum's columns, where asked for: ",lyapunov1,...,lyapunovN"
std::string lyapunov_header(std::size_t dimension) {
  std::string header;
  for (std::size_t i = 1; i <= dimension; ++i) header += fmt::format(",lyapunov{}", i);
  return header;
}

// row `row` of a row-major table of N exponents per row (-inf, nan as such)
std::string lyapunov_fields(const std::vector<double>& spectrum, std::size_t dimension,
                            std::size_t row) {
  std::string fields;
  for (std::size_t i = 0; i < dimension; ++i)
    fields += "," + number(spectrum[row * dimension + i]);
  return fields;
}

// basins.csv (each grid point's attractor) and attractors.csv (each
// attractor's class, canonical section point and basin size); returns the
// map's basin measures
BasinMeasures write_basins(RunFiles& run_files, const SweepPlan& plan,
                           const std::vector<SweepTask>& tasks,
                           const std::map<RecordKey, SweepRecord>& records,
                           std::vector<std::string>& files) {
  const BasinsTable table = basins_table(plan, tasks, records);
  AtomicFile& basins = run_files.add("basins.csv");
  basins.stream() << plan.axes[0].name << ',' << plan.axes[1].name
                  << ",attractor,period,impacts_per_period,contact,termination,transient_end"
                  << lyapunov_header(table.lyapunov_dimension) << '\n';
  for (std::size_t k = 0; k < table.x.size(); ++k)
    basins.stream() << number(table.x[k]) << ',' << number(table.y[k]) << ','
                    << table.attractor[k] << ',' << table.period[k] << ','
                    << number(table.impacts_per_period[k]) << ',' << table.contact[k] << ','
                    << to_string(table.termination[k]) << ',' << to_string(table.transient_end[k])
                    << lyapunov_fields(table.lyapunov_spectrum, table.lyapunov_dimension, k)
                    << '\n';
  AtomicFile& attractors = run_files.add("attractors.csv");
  attractors.stream() << "attractor,period,impacts_per_period,contact,q,qdot,basin_points\n";
  const AttractorRows rows = attractor_rows(table.map);
  for (std::size_t k = 0; k < rows.id.size(); ++k)
    attractors.stream() << rows.id[k] << ',' << rows.period[k] << ','
                        << number(rows.impacts_per_period[k]) << ',' << rows.contact[k] << ','
                        << number(rows.q[k]) << ',' << number(rows.qdot[k]) << ','
                        << rows.basin_points[k] << '\n';
  files = {"basins.csv", "attractors.csv"};
  return table.measures;
}

// attractors.csv (each attractor at each value: features, basin fraction and
// its error), attractor_points.csv (each attractor's section points) and
// samples.csv (each sample's initial state and attractor); returns the table
// for meta.json's events and the summary line
AttractorsTable write_attractors(RunFiles& run_files, const SweepPlan& plan,
                                 const std::vector<SweepTask>& tasks,
                                 const std::map<RecordKey, SweepRecord>& records,
                                 std::vector<std::string>& files) {
  AttractorsTable table = attractors_table(plan, tasks, records);
  const std::string& name = plan.axes[0].name;
  const auto& rows = table.attractors;
  AtomicFile& attractors = run_files.add("attractors.csv");
  attractors.stream() << name
                      << ",attractor,period,impacts_per_cycle,impacts_per_period,contact,"
                         "contact_phases_per_period,min_impact_speed,q,qdot,lyapunov,samples,"
                         "fraction,fraction_error\n";
  for (std::size_t k = 0; k < rows.id.size(); ++k)
    attractors.stream() << number(rows.value[k]) << ',' << rows.id[k] << ',' << rows.period[k]
                        << ',' << rows.impacts_per_cycle[k] << ','
                        << number(rows.impacts_per_period[k]) << ',' << rows.contact[k] << ','
                        << number(rows.contact_phases_per_period[k]) << ','
                        << number(rows.min_impact_speed[k]) << ',' << number(rows.q[k]) << ','
                        << number(rows.qdot[k]) << ',' << number(rows.lyapunov[k]) << ','
                        << rows.samples[k] << ',' << number(rows.fraction[k]) << ','
                        << number(rows.fraction_error[k]) << '\n';
  const auto& points = table.points;
  AtomicFile& point_file = run_files.add("attractor_points.csv");
  point_file.stream() << name << ",attractor,k,q,qdot\n";
  for (std::size_t k = 0; k < points.id.size(); ++k)
    point_file.stream() << number(points.value[k]) << ',' << points.id[k] << ',' << points.k[k]
                        << ',' << number(points.q[k]) << ',' << number(points.qdot[k]) << '\n';
  const auto& samples = table.samples;
  AtomicFile& sample_file = run_files.add("samples.csv");
  sample_file.stream() << name << ",sample";
  for (const BoxRange& range : plan.box) sample_file.stream() << ',' << range.key;
  sample_file.stream() << ",attractor,period,impacts_per_period,contact,termination,"
                          "transient_end\n";
  for (std::size_t k = 0; k < samples.value.size(); ++k) {
    sample_file.stream() << number(samples.value[k]) << ',' << samples.sample[k];
    for (const auto& column : samples.box) sample_file.stream() << ',' << number(column[k]);
    sample_file.stream() << ',' << samples.attractor[k] << ',' << samples.period[k] << ','
                         << number(samples.impacts_per_period[k]) << ',' << samples.contact[k]
                         << ',' << to_string(samples.termination[k]) << ','
                         << to_string(samples.transient_end[k]) << '\n';
  }
  files = {"attractors.csv", "attractor_points.csv", "samples.csv"};
  return table;
}

// bifurcation.csv and summary.csv (1D) or classes.csv (2D). `table` holds the
// summary rows; a 1D sweep's section points are read back from the
// checkpoints record by record, in the rows' order.
void write_outputs(RunFiles& run_files, const SweepPlan& plan, const std::vector<SweepTask>& tasks,
                   const SweepTable& table, const SweepCheckpoints& checkpoints,
                   std::vector<std::string>& files) {
  auto summary_fields = [&](std::size_t row) {
    return fmt::format("{},{},{},{},{}", table.period[row], number(table.impacts_per_period[row]),
                       table.contact[row], number(table.lyapunov[row]),
                       to_string(table.termination[row]));
  };
  auto transient_fields = [&](std::size_t row) {
    return fmt::format("{},{}", number(table.transient_periods[row]),
                       to_string(table.transient_end[row]));
  };
  auto direction_name = [](int direction) { return direction > 0 ? "up" : "down"; };
  if (plan.axes.size() == 1) {
    const SweepAxis& axis = plan.axes[0];
    AtomicFile& bifurcation = run_files.add("bifurcation.csv");
    AtomicFile& summary = run_files.add("summary.csv");
    bifurcation.stream() << axis.name << ",k,t,q,qdot,wall,direction\n";
    summary.stream() << axis.name
                     << ",direction,period,impacts_per_period,contact,lyapunov,termination,"
                        "points,stick_fraction,transient_periods,transient_end"
                     << lyapunov_header(table.lyapunov_dimension) << '\n';
    for (const SweepRecordKey& key : sweep_row_order(plan, tasks)) {
      SweepTable rows;
      add_bifurcation_rows(rows, plan, checkpoints.load(key));
      for (std::size_t row = 0; row < rows.point_value.size(); ++row)
        bifurcation.stream() << number(rows.point_value[row]) << ',' << rows.point_k[row] << ','
                             << number(rows.point_t[row]) << ',' << number(rows.point_q[row])
                             << ',' << number(rows.point_qdot[row]) << ','
                             << rows.point_wall[row] << ','
                             << direction_name(rows.point_direction[row]) << '\n';
    }
    for (std::size_t row = 0; row < table.value.size(); ++row)
      summary.stream() << number(table.value[row]) << ',' << direction_name(table.direction[row])
                       << ',' << summary_fields(row) << ',' << table.points[row] << ','
                       << number(table.stick_fraction[row]) << ',' << transient_fields(row)
                       << lyapunov_fields(table.lyapunov_spectrum, table.lyapunov_dimension, row)
                       << '\n';
    files = {"bifurcation.csv", "summary.csv"};
    return;
  }
  AtomicFile& classes = run_files.add("classes.csv");
  classes.stream() << plan.axes[0].name << ',' << plan.axes[1].name
                   << ",period,impacts_per_period,contact,lyapunov,termination,stick_fraction,"
                      "transient_periods,transient_end"
                   << lyapunov_header(table.lyapunov_dimension) << '\n';
  for (std::size_t row = 0; row < table.value.size(); ++row)
    classes.stream() << number(table.value[row]) << ',' << number(table.value2[row]) << ','
                     << summary_fields(row) << ',' << number(table.stick_fraction[row]) << ','
                     << transient_fields(row)
                     << lyapunov_fields(table.lyapunov_spectrum, table.lyapunov_dimension, row)
                     << '\n';
  files = {"classes.csv"};
}

// The sweep the options describe (api/sweep_job.hpp).
SweepSpec sweep_spec(const SweepOptions& options) {
  SweepSpec spec;
  spec.params = options.params;
  spec.direction = options.direction;
  spec.chunks = options.chunks;
  spec.section = options.section.request();
  spec.section.lyapunov_spectrum = options.lyapunov_spectrum;
  if (options.lyapunov) spec.lyapunov = true;
  if (options.no_lyapunov) spec.lyapunov = false;
  spec.period_tolerance = options.period_tolerance;
  spec.max_period = options.max_period;
  spec.classification_tolerance = options.classification_tolerance;
  return spec;
}

// The basins map the options describe (api/basins_job.hpp).
BasinsSpec basins_spec(const SweepOptions& options) {
  BasinsSpec spec;
  spec.x = options.params.at(0);
  spec.y = options.params.at(1);
  spec.section = options.section.request();
  spec.section.lyapunov_spectrum = options.lyapunov_spectrum;
  spec.lyapunov = options.lyapunov;  // off unless asked for
  spec.period_tolerance = options.period_tolerance;
  spec.max_period = options.max_period;
  spec.attractor_tolerance = options.attractor_tolerance;
  if (options.entropy_box > 0) spec.entropy_box = options.entropy_box;
  return spec;
}

// The attractors job the options describe (api/attractors_job.hpp).
AttractorsSpec attractors_spec(const SweepOptions& options) {
  AttractorsSpec spec;
  spec.param = options.params.at(0);
  spec.samples = options.samples;
  spec.box = options.box;
  spec.seed = options.seed;
  spec.section = options.section.request();
  spec.lyapunov = options.lyapunov;  // off unless asked for
  spec.period_tolerance = options.period_tolerance;
  spec.max_period = options.max_period;
  spec.attractor_tolerance = options.attractor_tolerance;
  spec.match_tolerance = options.match_tolerance;
  return spec;
}

// This rank's checkpoint, opened for appending; one that is not this
// sweep's (or any, without --resume) is started afresh with the header.
std::ofstream open_checkpoint(const std::filesystem::path& path, const std::string& header,
                              bool resume) {
  {
    std::ifstream existing(path);
    std::string first;
    const bool keep = resume && std::getline(existing, first) && first == header;
    if (keep) {
      // a last line cut short by a kill is dropped, so that the lines
      // appended now each begin a line of their own
      existing.clear();
      existing.seekg(0);
      const std::string text((std::istreambuf_iterator<char>(existing)),
                             std::istreambuf_iterator<char>());
      existing.close();
      const std::size_t last_break = text.rfind('\n');
      if (last_break != std::string::npos && last_break + 1 < text.size())
        std::filesystem::resize_file(path, last_break + 1);
    } else {
      std::ofstream fresh(path, std::ios::trunc);
      fresh << header << '\n' << std::flush;
      if (!fresh) throw OutputError("cannot write the checkpoint " + path.string());
    }
  }
  std::ofstream checkpoint(path, std::ios::app);
  if (!checkpoint) throw OutputError("cannot write the checkpoint " + path.string());
  return checkpoint;
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
                const std::vector<std::string>& command_line, std::vector<std::string> files,
                const std::optional<BasinMeasures>& basin_measures,
                const std::optional<nlohmann::json>& attractor_events) {
  files.push_back("meta.json");
  const std::string q_name(schema.main_coordinate);
  nlohmann::json meta = {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"command", command_line},
      {"created_utc", utc_now()},
      {"sweep", definition},
      {"scene", scene_record(scene)},
      {"run", std::move(run)},
      {"counts", sweep_counts(all)},
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
        {"contact", "1 if a contact (sticking/sliding) phase began or ended in the record window, "
                    "or lasted through it (at rest on a wall)"},
        {"lyapunov", "largest Lyapunov exponent (1/time unit); nan where not computed, -inf "
                     "where nearby states merge (rest on a wall)"},
        {"lyapunov1..N", "with lyapunov_spectrum: all N Lyapunov exponents, largest first "
                         "(1/time unit; QR re-orthonormalisation); nan where not computed, "
                         "-inf for a direction the contact collapses"},
        {"termination", "completed, stopped_by_model, no_progress, ..."},
        {"points", "section points recorded"},
        {"stick_fraction", "share of the record window's impacts whose impulse stuck (friction "
                           "stopped the slip; the rigid model, else 0); nan without impacts"},
        {"transient_periods", "forcing periods the point's transient ran"},
        {"transient_end",
         "how the transient ended: settled (the stroboscopic points repeat), not_periodic "
         "(they neither repeat nor converge: chaos, a torus, a period over max_period), "
         "not_settled (still converging at max_transient: the period may be a transient's), "
         "fixed (an explicit transient)"},
        {"attractor", "basins: the attractor the point settles on (attractors.csv; 0: none found)"},
        {"basin_points", "basins: grid points that settle on the attractor"},
        {"sample", "attractors: the sample's index at this value (its initial state drawn "
                   "from the box with the seed, meta.json's sweep)"},
        {"impacts_per_cycle", "attractors: n of the (m, n) label, impacts in the period m "
                              "forcing periods of the cycle"},
        {"contact_phases_per_period", "attractors: contact phases begun or ended per forcing "
                                      "period"},
        {"min_impact_speed", "attractors: smallest |qdot| just before an impact over the "
                             "attractor's samples (" + q_name + " per time unit): the distance "
                             "to grazing; nan without impacts"},
        {"samples", "attractors: samples that settle on the attractor at this value"},
        {"fraction", "attractors: its basin fraction, samples / K"},
        {"fraction_error", "attractors: the binomial standard error sqrt(f (1 - f) / K)"}}},
      {"files", files},
  };
  if (basin_measures) meta["basin_measures"] = basin_measures_record(*basin_measures);
  if (attractor_events) meta["attractor_events"] = *attractor_events;
  write_json(run_files.add("meta.json"), meta);
}

int run_sweep_command(const SweepOptions& options, const std::vector<std::string>& command_line) {
  const Scene scene = options.section.scene.load();
  const SweepTarget target = sweep_target(scene);
  const SceneSchema& schema = *target.schema;
  const SweepPlan plan =
      options.attractors ? make_attractors_plan(attractors_spec(options), scene, schema)
      : options.basins   ? make_basins_plan(basins_spec(options), scene, schema)
                         : make_sweep_plan(sweep_spec(options), scene, schema);
  const auto directory = options.section.scene.output_directory();
  // the sweep's data files and meta.json, committed together by rank 0
  // rank 0 owns the directory (its lock, its commit); the other ranks of one
  // mpirun share it, writing their checkpoints only
  RunFiles run_files = open_run_files(directory, MpiSession::launched_rank() == 0);
  // MPI starts once the input is known to be good: bad input exits with
  // status 2 on every rank alike, before any rank waits for another
  MpiSession mpi;

  const nlohmann::json section_record =
      section_request_record(options.section.section, plan.section);
  const nlohmann::json definition =
      options.attractors ? attractors_definition(plan, scene, schema, section_record)
      : options.basins   ? basins_definition(plan, scene, schema, section_record)
                         : sweep_definition(plan, scene, schema, section_record);
  const std::string header = nlohmann::json{{"impactlab_sweep_checkpoint", definition}}.dump();
  // basins and attractors tell attractors apart by their section points:
  // their records keep them; a sweep's records shed them once they are in the
  // checkpoint
  const bool keep_points = options.basins || options.attractors;
  std::map<RecordKey, SweepRecord> done;
  if (options.resume) done = SweepCheckpoints(directory, header, keep_points).records();
  const std::filesystem::path checkpoint_path = directory / sweep_checkpoint_name(mpi.rank());
  std::ofstream checkpoint = open_checkpoint(checkpoint_path, header, options.resume);

  // this rank's share: task id mod ranks
  const std::vector<SweepTask> tasks = sweep_tasks(plan);
  std::vector<const SweepTask*> mine;
  std::size_t total_points = 0;
  for (const auto& task : tasks) {
    total_points += task.points.size();
    if (task.id % mpi.size() == mpi.rank()) mine.push_back(&task);
  }
  const auto start = std::chrono::steady_clock::now();
  ProgressBar progress(!options.section.scene.quiet && mpi.rank() == 0);
  SweepJobOptions job;
  job.threads = options.threads;
  job.batch = options.batch;
  job.done = &done;
  job.on_record = [&checkpoint, &checkpoint_path](const SweepRecord& record) {
    checkpoint << sweep_checkpoint_line(record) << '\n' << std::flush;
    if (!checkpoint)
      throw OutputError("writing the checkpoint " + checkpoint_path.string() + " failed");
  };
  job.progress = [&progress](double fraction) { progress.update(fraction); };
  job.stop_after = options.stop_after;
  job.keep_points = keep_points;
  SweepOutput work = run_sweep(scene, target, plan, mine, job);
  // every line flushed and the file closed before rank 0 reads it back
  checkpoint.close();
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // every rank's records to rank 0, which writes; one rank keeps its own
  // (to_json_line and from_json_line are each other's inverse, so the files
  // are the same either way)
  std::map<RecordKey, SweepRecord> all;
  if (mpi.size() == 1) {
    for (auto& records : work.records)
      for (auto& record : records) {
        const RecordKey key{record.task, record.position};
        all.emplace(key, std::move(record));
      }
  } else {
    std::string text;
    for (const auto& records : work.records)
      for (const auto& record : records) text += to_json_line(record) + '\n';
    const std::vector<std::string> gathered = mpi.gather(text);
    if (mpi.rank() != 0) return work.stopped ? exit_stopped_early : exit_done;
    all = parse_records(gathered);
  }
  if (all.size() < total_points) {
    std::cerr << fmt::format(
        "impactlab: sweep stopped after {} of {} points (checkpoint in {}); run again with "
        "--resume to finish it\n",
        all.size(), total_points, directory.string());
    return exit_stopped_early;
  }

  std::vector<std::string> files;
  std::optional<BasinMeasures> basin_measures;
  std::optional<nlohmann::json> attractor_events;
  std::string attractors_summary;
  if (options.attractors) {
    const AttractorsTable table = write_attractors(run_files, plan, tasks, all, files);
    attractor_events = attractor_events_record(table, plan);
    attractors_summary = attractors_line(table);
  } else if (options.basins)
    basin_measures = write_basins(run_files, plan, tasks, all, files);
  else
    write_outputs(run_files, plan, tasks, sweep_table(plan, tasks, all),
                  SweepCheckpoints(directory, header, false), files);
  write_meta(run_files, definition, scene, *target.schema, all,
             {{"threads", options.threads},
              {"batch_width", work.batch_width},
              {"mpi_ranks", mpi.size()},
              {"tasks", tasks.size()},
              {"points_reused_from_checkpoint", done.size()},
              {"wall_time_s", wall_time}},
             command_line, files, basin_measures, attractor_events);
  run_files.commit();
  // the sweep is complete: its checkpoints (of any rank count) are spent
  for (const auto& file : std::filesystem::directory_iterator(directory)) {
    const std::string name = file.path().filename().string();
    if (name.starts_with("checkpoint-") && name.ends_with(".jsonl"))
      std::filesystem::remove(file.path());
  }

  const std::string q_name(target.schema->main_coordinate);
  if (options.section.plot) {
    if (options.attractors)
      plot_with_python("attractors", directory / "attractors.csv",
                       directory / "attractors.png", {plan.axes[0].name, q_name});
    else if (options.basins)
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
  if (basin_measures && !options.section.scene.quiet)
    std::cout << basin_measures_line(*basin_measures) << '\n';
  if (!attractors_summary.empty() && !options.section.scene.quiet)
    std::cout << attractors_summary << '\n';
  // the file whose termination and transient_end columns say which points
  const std::string row_file = options.attractors ? "samples.csv"
                               : options.basins   ? "basins.csv"
                               : plan.axes.size() == 1 ? "summary.csv"
                                                       : "classes.csv";
  // said even when quiet: a stopped point is a gap in the diagram otherwise
  if (const std::string stopped = stopped_points_note(all); !stopped.empty())
    std::cerr << "impactlab: warning: " << stopped << "; the termination column of "
              << row_file << " says which\n";
  if (const std::string unsettled = unsettled_points_note(all, plan); !unsettled.empty())
    std::cerr << "impactlab: warning: " << unsettled << " (the transient_end column of "
              << row_file << ")\n";
  return exit_done;
}

}  // namespace

Command add_sweep_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "sweep",
      "1D bifurcation sweep (bifurcation.csv, summary.csv) or 2D classification map "
      "(classes.csv) over scene parameters");
  auto options = std::make_shared<SweepOptions>();
  TableOptions table(*command, "sweep");
  options->section.add_to(table);
  table.add("param", options->params);
  table.add("direction", options->direction);
  table.add("threads", options->threads);
  table.add("batch", options->batch);
  table.add("chunks", options->chunks);
  table.add("lyapunov", options->lyapunov);
  table.add("no_lyapunov", options->no_lyapunov);
  table.add("lyapunov_spectrum", options->lyapunov_spectrum);
  table.add("period_tol", options->period_tolerance);
  table.add("max_period", options->max_period);
  table.add("classification_tol", options->classification_tolerance);
  table.add("resume", options->resume);
  table.add("stop_after", options->stop_after);
  return {command,
          [options](const std::vector<std::string>& command_line) {
            return run_sweep_command(*options, command_line);
          },
          "sweep"};
}

Command add_basins_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "basins",
      "basins of attraction: each initial condition of a 2D grid (e.g. initial.theta x "
      "initial.theta_dot) classified by the attractor it settles on (basins.csv, attractors.csv)");
  auto options = std::make_shared<SweepOptions>();
  options->basins = true;
  options->params.resize(2);
  TableOptions table(*command, "basins");
  options->section.add_to(table);
  table.add("x", options->params[0]);
  table.add("y", options->params[1]);
  table.add("threads", options->threads);
  table.add("batch", options->batch);
  table.add("lyapunov", options->lyapunov);
  table.add("lyapunov_spectrum", options->lyapunov_spectrum);
  table.add("period_tol", options->period_tolerance);
  table.add("max_period", options->max_period);
  table.add("attractor_tol", options->attractor_tolerance);
  table.add("entropy_box", options->entropy_box);
  table.add("resume", options->resume);
  table.add("stop_after", options->stop_after);
  return {command,
          [options](const std::vector<std::string>& command_line) {
            return run_sweep_command(*options, command_line);
          },
          "basins"};
}

Command add_attractors_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "attractors",
      "attractors found and followed across a parameter: at each value, initial states sampled "
      "from a box, each run to its attractor (attractors.csv with basin fractions, "
      "attractor_points.csv, samples.csv; appear/vanish/merge events in meta.json)");
  auto options = std::make_shared<SweepOptions>();
  options->attractors = true;
  options->params.resize(1);
  TableOptions table(*command, "attractors");
  options->section.add_to(table);
  table.add("param", options->params[0]);
  table.add("samples", options->samples);
  table.add("box", options->box);
  table.add("seed", options->seed);
  table.add("threads", options->threads);
  table.add("batch", options->batch);
  table.add("lyapunov", options->lyapunov);
  table.add("period_tol", options->period_tolerance);
  table.add("max_period", options->max_period);
  table.add("attractor_tol", options->attractor_tolerance);
  table.add("match_tol", options->match_tolerance);
  table.add("resume", options->resume);
  table.add("stop_after", options->stop_after);
  return {command,
          [options](const std::vector<std::string>& command_line) {
            return run_sweep_command(*options, command_line);
          },
          "attractors"};
}

}  // namespace impactlab::cli
