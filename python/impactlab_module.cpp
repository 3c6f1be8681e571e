// The compiled part of the Python package impactlab: thin bindings of the
// scene API (api/) for python/impactlab/__init__.py, which adds the
// keyword handling, the result classes and the warnings. Every job runs with
// the GIL released; its progress callback takes the GIL back now and then to
// call the user's callback and to look for Ctrl-C, and a Python exception
// there cancels the job and comes out of the call unchanged.
#include <cxxabi.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstddef>
#include <exception>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <type_traits>
#include <variant>
#include <vector>

#include <pybind11/complex.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/api/attractors_job.hpp>
#include <impactlab/api/basins_job.hpp>
#include <impactlab/api/compare.hpp>
#include <impactlab/api/grazing_record.hpp>
#include <impactlab/api/continuation_job.hpp>
#include <impactlab/api/job_options.hpp>
#include <impactlab/api/model_keys.hpp>
#include <impactlab/api/periodic_job.hpp>
#include <impactlab/api/every_orbit_continuation.hpp>
#include <impactlab/api/run_record.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/scene_record.hpp>
#include <impactlab/api/section_record.hpp>
#include <impactlab/api/sweep_job.hpp>
#include <impactlab/api/work_precision.hpp>
#include <impactlab/integrate/stepper_names.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/builtin_scenes.hpp>
#include <impactlab/io/message_text.hpp>
#include <impactlab/io/output_error.hpp>
#include <impactlab/io/scene_file.hpp>

namespace py = pybind11;
using namespace impactlab;

namespace {

// Thrown through a job (with the GIL released) when the Python side raised
// in a progress callback, or when the interpreter began to exit; the Python
// error is kept and restored afterwards.
struct Cancelled {};

// Whether the interpreter is exiting. A thread that takes the GIL then never
// returns: CPython ends it on the spot (pthread_exit, a forced unwind), and
// one taken from a destructor, which may not throw, ends the whole process
// ("terminate called without an active exception"). Read without the GIL.
bool interpreter_exiting() {
#if PY_VERSION_HEX >= 0x030D0000
  return Py_IsFinalizing() != 0;
#else
  return _Py_IsFinalizing() != 0;
#endif
}

// Progress of one job: the user's callback and the Ctrl-C check. The check
// takes the GIL at most every `check_interval`, so that a short run pays
// nothing for it. While the interpreter exits, the job is cancelled without
// touching Python, and the thread that ran it waits for the process to end
// rather than take the GIL back.
class ProgressRelay {
 public:
  explicit ProgressRelay(py::object callback) : callback_(std::move(callback)) {}

  // called from the job, without the GIL; throws Cancelled
  void operator()(double fraction) {
    if (interpreter_exiting()) throw Cancelled{};
    const auto now = std::chrono::steady_clock::now();
    if (callback_.is_none() && now - last_check_ < check_interval) return;
    last_check_ = now;
    py::gil_scoped_acquire gil;
    try {
      if (!callback_.is_none()) callback_(fraction);
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    } catch (py::error_already_set& error) {
      error_ = std::make_unique<py::error_already_set>(std::move(error));
      throw Cancelled{};
    }
  }

  // runs `job` without the GIL; a cancellation re-raises the Python error.
  // The GIL is taken back by an explicit call, outside any destructor and
  // any handler, so that a thread CPython ends there unwinds cleanly.
  template <class Job>
  auto run(Job&& job) {
    using Result = decltype(job());
    std::conditional_t<std::is_void_v<Result>, bool, std::optional<Result>> result{};
    std::exception_ptr failure;
    PyThreadState* thread_state = PyEval_SaveThread();
    try {
      if constexpr (std::is_void_v<Result>)
        job();
      else
        result.emplace(job());
    } catch (abi::__forced_unwind&) {
      throw;  // the thread is being ended: let it go
    } catch (...) {
      failure = std::current_exception();
    }
    // the interpreter is exiting: this thread must not take the GIL again;
    // the process ends around it
    while (interpreter_exiting()) std::this_thread::sleep_for(std::chrono::seconds(1));
    PyEval_RestoreThread(thread_state);
    if (failure) {
      try {
        std::rethrow_exception(failure);
      } catch (const Cancelled&) {
        if (!error_) throw;
      }
      throw std::move(*error_);
    }
    if constexpr (!std::is_void_v<Result>) return std::move(*result);
  }

 private:
  static constexpr std::chrono::milliseconds check_interval{20};
  py::object callback_;
  std::chrono::steady_clock::time_point last_check_ = std::chrono::steady_clock::now();
  std::unique_ptr<py::error_already_set> error_;
};

// A NumPy array over a vector's data without a copy: the vector moves into
// the array's base object.
template <class T>
py::array owning_array(std::vector<T>&& values) {
  auto* owner = new std::vector<T>(std::move(values));
  py::capsule base(owner, [](void* pointer) { delete static_cast<std::vector<T>*>(pointer); });
  return py::array_t<T>({static_cast<py::ssize_t>(owner->size())}, owner->data(), base);
}

// One row of Python's events array: the core's record and what the model
// adds to it (io/event_extension.hpp), in events.csv's column order.
struct EventRow {
  EventRecord event;
  EventExtension extension;
};

// One column of the events array: its NumPy format, its offset in EventRow
// and its size (bytes).
struct EventField {
  const char* format;
  std::size_t offset;
  std::size_t size;
};

// Every column's field, by events.csv's column name.
const std::map<std::string_view, EventField>& event_fields() {
  constexpr std::size_t event = offsetof(EventRow, event), extension = offsetof(EventRow, extension);
  static const std::map<std::string_view, EventField> fields = {
      {"t", {"<f8", event + offsetof(EventRecord, t), 8}},
      {"kind", {"u1", event + offsetof(EventRecord, kind), 1}},
      {"wall", {"<i4", event + offsetof(EventRecord, wall), 4}},
      {"q", {"<f8", event + offsetof(EventRecord, q), 8}},
      {"qdot_before", {"<f8", event + offsetof(EventRecord, qdot_before), 8}},
      {"qdot_after", {"<f8", event + offsetof(EventRecord, qdot_after), 8}},
      {"normal_impulse", {"<f8", event + offsetof(EventRecord, normal_impulse), 8}},
      {"tangential_velocity", {"<f8", event + offsetof(EventRecord, tangential_velocity), 8}},
      {"normal_force", {"<f8", event + offsetof(EventRecord, normal_force), 8}},
      {"friction_work", {"<f8", event + offsetof(EventRecord, friction_work), 8}},
      {"instantaneous_residual",
       {"<f8", extension + offsetof(EventExtension, instantaneous_residual), 8}},
      {"sliding_residual", {"<f8", extension + offsetof(EventExtension, sliding_residual), 8}},
      {"tangential_velocity_after",
       {"<f8", event + offsetof(EventRecord, tangential_velocity_after), 8}},
      {"accumulation_error", {"<f8", event + offsetof(EventRecord, accumulation_error), 8}}};
  static_assert(sizeof(EventKind) == 1 && sizeof(int) == 4);
  return fields;
}

// The structured dtype of EventRow, field by field at its C++ offsets, for
// the columns of a run's events.csv (the core's and its model's own), so that
// the event log is one array (the rows copied once, with their extensions).
py::dtype event_dtype(const EventColumns& columns) {
  py::list names, formats, offsets;
  for (const std::string_view name : columns.names()) {
    const EventField& field = event_fields().at(name);
    names.append(py::str(std::string(name)));
    formats.append(field.format);
    offsets.append(field.offset);
  }
  py::dict spec;
  spec["names"] = names;
  spec["formats"] = formats;
  spec["offsets"] = offsets;
  spec["itemsize"] = sizeof(EventRow);
  return py::dtype::from_args(spec);
}

// The events of a run of `scene`, each with its extension, in `columns` (the
// run's events.csv's, RunOutput::event_columns). The bytes of a row that no
// column reads (the structs' padding, the fields this run's files do not
// have) are zero, so that the array's bytes, and what NumPy saves of them,
// are the same for the same run.
py::array event_array(const std::vector<EventRecord>& events, const EventColumns& columns,
                      const Scene& scene) {
  const EventExtender extender = event_extender(scene);
  std::array<bool, sizeof(EventRow)> read{};
  for (const std::string_view name : columns.names()) {
    const EventField& field = event_fields().at(name);
    std::fill_n(read.begin() + static_cast<std::ptrdiff_t>(field.offset), field.size, true);
  }
  auto* owner = new std::vector<EventRow>();
  owner->reserve(events.size());
  for (const EventRecord& event : events) {
    owner->push_back({event, extender ? extender(event) : EventExtension{}});
    auto* bytes = reinterpret_cast<unsigned char*>(&owner->back());
    for (std::size_t b = 0; b < read.size(); ++b)
      if (!read[b]) bytes[b] = 0;
  }
  py::capsule base(owner,
                   [](void* pointer) { delete static_cast<std::vector<EventRow>*>(pointer); });
  return py::array(event_dtype(columns), {static_cast<py::ssize_t>(owner->size())},
                   {}, owner->data(), base);
}

// The names of a table's terminations or transient ends, as the CLI's files
// write them.
template <class Outcome>
py::list outcome_names(const std::vector<Outcome>& outcomes) {
  py::list names;
  for (const Outcome outcome : outcomes) names.append(to_string(outcome));
  return names;
}

py::object json_to_python(const nlohmann::json& document) {
  return py::module_::import("json").attr("loads")(document.dump());
}

// What meta.json records of a run, made when Python asks for it (most calls
// never do): the scene and the run's counters, without its events and samples.
struct PendingRunRecord {
  Scene scene;
  RunOutput output;  // events and samples moved out (output.event_count counts them)

  [[nodiscard]] py::object meta() const { return json_to_python(run_record(scene, output)); }
};

py::dict simulate_binding(const Scene& scene, double periods, double t_end, double sample_step,
                          py::object progress) {
  RunRequest request;
  if (t_end != 0.0) {
    request.periods = 0.0;
    request.t_end = t_end;
  } else {
    request.periods = periods;
  }
  request.sample_step = sample_step;
  ProgressRelay relay(std::move(progress));
  request.progress = [&relay](double fraction) { relay(fraction); };
  RunOutput output = relay.run([&] { return simulate(scene, request); });

  py::dict result;
  result["termination"] = to_string(output.termination);
  // samples: t, q, qdot as arrays, the mode names as a list
  std::vector<double> t, q, qdot;
  py::list modes;
  for (const auto& sample : output.samples) {
    t.push_back(sample.t);
    q.push_back(sample.q);
    qdot.push_back(sample.qdot);
    modes.append(py::str(sample.mode.data(), sample.mode.size()));
  }
  result["samples_t"] = owning_array(std::move(t));
  result["samples_q"] = owning_array(std::move(q));
  result["samples_qdot"] = owning_array(std::move(qdot));
  result["samples_mode"] = modes;
  result["events"] = event_array(output.events, output.event_columns, scene);
  output.events = {};  // the array holds its own rows
  output.samples.clear();
  result["record"] = PendingRunRecord{scene, std::move(output)};
  return result;
}

// `transient` None: the settling transient (the options table's default)
SectionRequest section_request(const std::string& section, std::optional<double> transient,
                               double max_transient, std::uint64_t transient_impacts,
                               std::uint64_t points, bool lyapunov, bool lyapunov_spectrum) {
  SectionRequest request;
  request.lyapunov_spectrum = lyapunov_spectrum;
  request.section = parse_section(section, "section");
  request.settle = !transient.has_value();
  if (transient) request.transient_periods = *transient;
  request.max_transient_periods = max_transient;
  request.transient_impacts = transient_impacts;
  request.points = points;
  request.lyapunov = lyapunov;
  return request;
}

py::dict section_arrays(const SectionResult& result) {
  std::vector<double> t, q, qdot;
  std::vector<int> wall;
  for (const auto& p : result.points) {
    t.push_back(p.t);
    q.push_back(p.q);
    qdot.push_back(p.qdot);
    wall.push_back(p.wall);
  }
  py::dict arrays;
  arrays["t"] = owning_array(std::move(t));
  arrays["q"] = owning_array(std::move(q));
  arrays["qdot"] = owning_array(std::move(qdot));
  arrays["wall"] = owning_array(std::move(wall));
  return arrays;
}

// The running estimate of a spectrum kept in memory: one row of N per period
// (Python reshapes the values by the spectrum's N).
class LyapunovRows final : public LyapunovSpectrumSink {
 public:
  void begin(std::size_t) override {}
  void write(double t, const std::vector<double>& running) override {
    times.push_back(t);
    values.insert(values.end(), running.begin(), running.end());
  }
  std::vector<double> times, values;  // values row-major, times.size() × N
};

py::dict poincare_binding(const Scene& scene, const std::string& section,
                          std::optional<double> transient, double max_transient,
                          std::uint64_t transient_impacts, std::uint64_t points, bool lyapunov,
                          bool lyapunov_spectrum, py::object progress) {
  SectionRequest request = section_request(section, transient, max_transient, transient_impacts,
                                           points, lyapunov, lyapunov_spectrum);
  LyapunovRows running;
  if (lyapunov_spectrum) request.lyapunov_spectrum_sink = &running;
  ProgressRelay relay(std::move(progress));
  // a Poincaré run reports no progress of its own: the check runs once after it
  const SectionResult result = relay.run([&] { return poincare(scene, request); });
  relay(1.0);
  py::dict out = section_arrays(result);
  out["termination"] = to_string(result.termination);
  out["omega"] = result.omega;
  out["forcing_period"] = result.forcing_period;
  out["record_start"] = result.record_start;
  out["transient_periods"] = result.transient_periods;
  out["transient_end"] = to_string(result.transient_end);
  out["periods_recorded"] = result.periods_recorded;
  out["impacts"] = result.impacts;
  out["contact_phases"] = result.contact_phases;
  out["steps"] = result.steps;
  out["rhs_evaluations"] = result.rhs_evaluations;
  out["lyapunov"] = result.lyapunov;
  out["lyapunov_note"] = result.lyapunov_note;
  if (lyapunov_spectrum) {
    out["lyapunov_spectrum"] = owning_array(std::vector<double>(result.lyapunov_spectrum));
    out["lyapunov_spectrum_error"] =
        owning_array(std::vector<double>(result.lyapunov_spectrum_error));
    out["lyapunov_spectrum_note"] = result.lyapunov_spectrum_note;
    out["lyapunov_running_t"] = owning_array(std::move(running.times));
    out["lyapunov_running"] = owning_array(std::move(running.values));
  }
  return out;
}

// A whole sweep plan run in this process (sweep and basins): every task over
// `threads`, progress and Ctrl-C through the relay, the records by key.
struct PlanRun {
  std::vector<SweepTask> tasks;
  std::map<SweepRecordKey, SweepRecord> records;
  double wall_time = 0.0;  // s
  int batch_width = 1;     // lanes per thread (api/sweep_job.hpp)
};

PlanRun run_plan(const Scene& scene, const SweepTarget& target, const SweepPlan& plan,
                 int threads, const std::string& batch, py::object progress) {
  PlanRun run;
  run.tasks = sweep_tasks(plan);
  std::vector<const SweepTask*> all_tasks;
  for (const auto& task : run.tasks) all_tasks.push_back(&task);
  ProgressRelay relay(std::move(progress));
  SweepJobOptions job;
  job.threads = threads;
  job.batch = batch;
  job.progress = [&relay](double fraction) { relay(fraction); };
  const auto start = std::chrono::steady_clock::now();
  SweepOutput output = relay.run([&] { return run_sweep(scene, target, plan, all_tasks, job); });
  run.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.batch_width = output.batch_width;
  for (auto& task_records : output.records)
    for (auto& record : task_records)
      run.records.emplace(SweepRecordKey{record.task, record.position}, std::move(record));
  return run;
}

py::dict sweep_binding(const Scene& scene, const std::vector<std::string>& params,
                       const std::string& direction, int chunks, const std::string& section,
                       std::optional<double> transient, double max_transient,
                       std::uint64_t transient_impacts, std::uint64_t points,
                       std::optional<bool> lyapunov, bool lyapunov_spectrum,
                       double period_tolerance, int max_period,
                       const std::string& classification_tolerance, int threads,
                       const std::string& batch, py::object progress) {
  SweepSpec spec;
  spec.params = params;
  spec.direction = direction;
  spec.chunks = chunks;
  spec.section =
      section_request(section, transient, max_transient, transient_impacts, points, false,
                      lyapunov_spectrum);
  spec.lyapunov = lyapunov;
  spec.period_tolerance = period_tolerance;
  spec.max_period = max_period;
  spec.classification_tolerance = classification_tolerance;
  const SweepTarget target = sweep_target(scene);
  const SweepPlan plan = make_sweep_plan(spec, scene, *target.schema);
  const PlanRun run = run_plan(scene, target, plan, threads, batch, std::move(progress));
  const double wall_time = run.wall_time;
  SweepTable table = sweep_table(plan, run.tasks, run.records);

  const nlohmann::json section_record = section_request_record(section, plan.section);
  py::dict out;
  out["definition"] = json_to_python(sweep_definition(plan, scene, *target.schema, section_record));
  out["axes"] = py::cast(std::vector<std::string>{plan.axes[0].name,
                                                  plan.axes.size() > 1 ? plan.axes[1].name : ""});
  out["point_value"] = owning_array(std::move(table.point_value));
  out["point_k"] = owning_array(std::move(table.point_k));
  out["point_t"] = owning_array(std::move(table.point_t));
  out["point_q"] = owning_array(std::move(table.point_q));
  out["point_qdot"] = owning_array(std::move(table.point_qdot));
  out["point_wall"] = owning_array(std::move(table.point_wall));
  out["point_direction"] = owning_array(std::move(table.point_direction));
  out["value"] = owning_array(std::move(table.value));
  out["value2"] = owning_array(std::move(table.value2));
  out["direction"] = owning_array(std::move(table.direction));
  out["period"] = owning_array(std::move(table.period));
  out["impacts_per_period"] = owning_array(std::move(table.impacts_per_period));
  out["contact"] = owning_array(std::move(table.contact));
  out["stick_fraction"] = owning_array(std::move(table.stick_fraction));
  out["lyapunov"] = owning_array(std::move(table.lyapunov));
  out["termination"] = outcome_names(table.termination);
  out["transient_periods"] = owning_array(std::move(table.transient_periods));
  out["transient_end"] = outcome_names(table.transient_end);
  out["lyapunov_dimension"] = table.lyapunov_dimension;
  out["lyapunov_spectrum"] = owning_array(std::move(table.lyapunov_spectrum));
  out["points"] = owning_array(std::move(table.points));
  out["wall_time_s"] = wall_time;
  out["stopped"] = stopped_points_note(run.records);
  out["unsettled"] = unsettled_points_note(run.records, plan);
  out["threads"] = threads;
  out["batch_width"] = run.batch_width;
  return out;
}

py::dict basins_binding(const Scene& scene, const std::string& x, const std::string& y,
                        const std::string& section, std::optional<double> transient,
                        double max_transient, std::uint64_t transient_impacts,
                        std::uint64_t points, bool lyapunov, bool lyapunov_spectrum,
                        double period_tolerance, int max_period, double attractor_tolerance,
                        std::optional<int> entropy_box, int threads, const std::string& batch,
                        py::object progress) {
  BasinsSpec spec;
  spec.x = x;
  spec.y = y;
  spec.section =
      section_request(section, transient, max_transient, transient_impacts, points, false,
                      lyapunov_spectrum);
  spec.lyapunov = lyapunov;
  spec.period_tolerance = period_tolerance;
  spec.max_period = max_period;
  spec.attractor_tolerance = attractor_tolerance;
  spec.entropy_box = entropy_box;
  const SweepTarget target = sweep_target(scene);
  const SweepPlan plan = make_basins_plan(spec, scene, *target.schema);
  const PlanRun run = run_plan(scene, target, plan, threads, batch, std::move(progress));
  const double wall_time = run.wall_time;
  BasinsTable table = basins_table(plan, run.tasks, run.records);
  AttractorRows attractors = attractor_rows(table.map);

  const nlohmann::json section_record = section_request_record(section, plan.section);
  const nlohmann::json meta = {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"sweep", basins_definition(plan, scene, *target.schema, section_record)},
      {"scene", scene_record(scene)},
      {"run",
       {{"threads", threads},
        {"batch_width", run.batch_width},
        {"tasks", run.tasks.size()},
        {"wall_time_s", wall_time}}},
      {"counts", sweep_counts(run.records)},
      {"basin_measures", basin_measures_record(table.measures)}};
  py::dict out;
  out["meta"] = json_to_python(meta);
  out["axes"] = py::cast(std::vector<std::string>{plan.axes[0].name, plan.axes[1].name});
  out["counts"] = py::cast(std::vector<int>{plan.axes[0].count, plan.axes[1].count});
  out["x"] = owning_array(std::move(table.x));
  out["y"] = owning_array(std::move(table.y));
  out["attractor"] = owning_array(std::move(table.attractor));
  out["period"] = owning_array(std::move(table.period));
  out["impacts_per_period"] = owning_array(std::move(table.impacts_per_period));
  out["contact"] = owning_array(std::move(table.contact));
  out["termination"] = outcome_names(table.termination);
  out["transient_end"] = outcome_names(table.transient_end);
  out["lyapunov_dimension"] = table.lyapunov_dimension;
  out["lyapunov_spectrum"] = owning_array(std::move(table.lyapunov_spectrum));
  out["attractor_id"] = owning_array(std::move(attractors.id));
  out["attractor_period"] = owning_array(std::move(attractors.period));
  out["attractor_impacts_per_period"] = owning_array(std::move(attractors.impacts_per_period));
  out["attractor_contact"] = owning_array(std::move(attractors.contact));
  out["attractor_q"] = owning_array(std::move(attractors.q));
  out["attractor_qdot"] = owning_array(std::move(attractors.qdot));
  out["attractor_basin_points"] = owning_array(std::move(attractors.basin_points));
  out["wall_time_s"] = wall_time;
  out["stopped"] = stopped_points_note(run.records);
  out["unsettled"] = unsettled_points_note(run.records, plan);
  return out;
}

// The attractors job's options in one struct (the binding's arguments, in
// the order Python passes them).
struct AttractorsArguments {
  std::string param;
  int samples = 0;
  std::vector<std::string> box;
  std::uint64_t seed = 0;
  std::string section;
  std::optional<double> transient;
  double max_transient = 0.0;
  std::uint64_t transient_impacts = 0, points = 0;
  bool lyapunov = false;
  double period_tolerance = 0.0;
  int max_period = 0;
  double attractor_tolerance = 0.0, match_tolerance = 0.0;
  int threads = 1;
  std::string batch;
};

py::dict attractors_binding(const Scene& scene, const AttractorsArguments& arguments,
                            py::object progress) {
  AttractorsSpec spec;
  spec.param = arguments.param;
  spec.samples = arguments.samples;
  spec.box = arguments.box;
  spec.seed = arguments.seed;
  spec.section = section_request(arguments.section, arguments.transient, arguments.max_transient,
                                 arguments.transient_impacts, arguments.points, false, false);
  spec.lyapunov = arguments.lyapunov;
  spec.period_tolerance = arguments.period_tolerance;
  spec.max_period = arguments.max_period;
  spec.attractor_tolerance = arguments.attractor_tolerance;
  spec.match_tolerance = arguments.match_tolerance;
  const SweepTarget target = sweep_target(scene);
  const SweepPlan plan = make_attractors_plan(spec, scene, *target.schema);
  const PlanRun run =
      run_plan(scene, target, plan, arguments.threads, arguments.batch, std::move(progress));
  AttractorsTable table = attractors_table(plan, run.tasks, run.records);

  const nlohmann::json section_record = section_request_record(arguments.section, plan.section);
  const nlohmann::json meta = {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"sweep", attractors_definition(plan, scene, *target.schema, section_record)},
      {"scene", scene_record(scene)},
      {"run",
       {{"threads", arguments.threads}, {"batch_width", run.batch_width}, {"tasks", run.tasks.size()},
        {"wall_time_s", run.wall_time}}},
      {"counts", sweep_counts(run.records)},
      {"attractor_events", attractor_events_record(table, plan)}};
  py::dict out;
  out["meta"] = json_to_python(meta);
  out["param"] = plan.axes[0].name;
  auto& rows = table.attractors;
  py::dict attractors;
  attractors["value"] = owning_array(std::move(rows.value));
  attractors["attractor"] = owning_array(std::move(rows.id));
  attractors["period"] = owning_array(std::move(rows.period));
  attractors["impacts_per_cycle"] = owning_array(std::move(rows.impacts_per_cycle));
  attractors["impacts_per_period"] = owning_array(std::move(rows.impacts_per_period));
  attractors["contact"] = owning_array(std::move(rows.contact));
  attractors["contact_phases_per_period"] = owning_array(std::move(rows.contact_phases_per_period));
  attractors["min_impact_speed"] = owning_array(std::move(rows.min_impact_speed));
  attractors["q"] = owning_array(std::move(rows.q));
  attractors["qdot"] = owning_array(std::move(rows.qdot));
  attractors["lyapunov"] = owning_array(std::move(rows.lyapunov));
  attractors["samples"] = owning_array(std::move(rows.samples));
  attractors["fraction"] = owning_array(std::move(rows.fraction));
  attractors["fraction_error"] = owning_array(std::move(rows.fraction_error));
  out["attractors"] = attractors;
  auto& points = table.points;
  py::dict point_columns;
  point_columns["value"] = owning_array(std::move(points.value));
  point_columns["attractor"] = owning_array(std::move(points.id));
  point_columns["k"] = owning_array(std::move(points.k));
  point_columns["q"] = owning_array(std::move(points.q));
  point_columns["qdot"] = owning_array(std::move(points.qdot));
  out["points"] = point_columns;
  auto& samples = table.samples;
  py::dict sample_columns;
  sample_columns["value"] = owning_array(std::move(samples.value));
  sample_columns["sample"] = owning_array(std::move(samples.sample));
  py::list box_columns;
  for (auto& column : samples.box) box_columns.append(owning_array(std::move(column)));
  sample_columns["box"] = box_columns;
  std::vector<std::string> box_keys;
  for (const BoxRange& range : plan.box) box_keys.push_back(range.key);
  sample_columns["box_keys"] = py::cast(box_keys);
  sample_columns["attractor"] = owning_array(std::move(samples.attractor));
  sample_columns["period"] = owning_array(std::move(samples.period));
  sample_columns["impacts_per_period"] = owning_array(std::move(samples.impacts_per_period));
  sample_columns["contact"] = owning_array(std::move(samples.contact));
  sample_columns["termination"] = outcome_names(samples.termination);
  sample_columns["transient_end"] = outcome_names(samples.transient_end);
  out["samples"] = sample_columns;
  out["wall_time_s"] = run.wall_time;
  out["stopped"] = stopped_points_note(run.records);
  out["unsettled"] = unsettled_points_note(run.records, plan);
  return out;
}

py::dict periodic_binding(const Scene& scene, const std::string& period, double phase,
                          double transient, int max_iterations, double tolerance,
                          py::object progress) {
  PeriodicJob job;
  job.period = period;
  job.phase = phase;
  job.transient = transient;
  job.max_iterations = max_iterations;
  job.tolerance = tolerance;
  ProgressRelay relay(std::move(progress));
  const PeriodicJobResult found = relay.run([&] { return find_periodic_orbit(scene, job); });
  relay(1.0);
  py::dict out;
  out["meta"] = json_to_python(periodic_record(scene, found));
  out["converged"] = found.result.converged;
  out["termination"] = to_string(found.result.termination);
  return out;
}

// periodic(all=True): the orbits' columns (orbits.csv's) and periodic.json's record
py::dict periodic_orbits_binding(const Scene& scene, const std::string& period, double phase,
                                 int max_iterations, double tolerance, int starts,
                                 const std::vector<std::string>& box, std::uint64_t seed,
                                 py::object progress) {
  PeriodicJob job;
  job.period = period;
  job.phase = phase;
  job.max_iterations = max_iterations;
  job.tolerance = tolerance;
  job.all = true;
  job.starts = starts;
  job.box = box;
  job.seed = seed;
  ProgressRelay relay(std::move(progress));
  const PeriodicOrbitsJobResult found =
      relay.run([&] { return find_periodic_orbits(scene, job, std::ref(relay)); });
  relay(1.0);
  py::dict columns;
  for (OrbitsColumn& column : periodic_orbits_table(found)) {
    if (column.whole) {
      std::vector<std::int64_t> whole(column.values.begin(), column.values.end());
      columns[py::str(column.name)] = owning_array(std::move(whole));
    } else {
      columns[py::str(column.name)] = owning_array(std::move(column.values));
    }
  }
  py::dict out;
  out["orbits"] = columns;
  out["meta"] = json_to_python(periodic_orbits_record(scene, found));
  return out;
}

py::dict compare_binding(const Scene& scene, const std::string& models, double periods,
                         double t_end, py::object progress) {
  RunRequest request;
  if (t_end != 0.0) {
    request.periods = 0.0;
    request.t_end = t_end;
  } else {
    request.periods = periods;
  }
  std::vector<std::string> skipped;
  const std::vector<std::string> names = models_to_compare(
      scene, models, [&skipped](const BadInput& bad) { skipped.emplace_back(bad.what()); });
  ProgressRelay relay(std::move(progress));
  request.progress = [&relay](double fraction) { relay(fraction); };
  Comparison comparison = relay.run([&] { return compare_models(scene, names, request); });
  const nlohmann::json numbers = comparison_numbers(comparison);
  std::ostringstream impacts, contacts, section;
  write_impacts_csv(impacts, comparison);
  write_contacts_csv(contacts, comparison);
  write_section_csv(section, comparison);
  py::dict out;
  out["numbers"] = json_to_python(numbers);
  out["summary"] = comparison_summary(comparison, numbers);
  out["impacts_csv"] = impacts.str();
  out["contacts_csv"] = contacts.str();
  out["section_csv"] = section.str();
  out["skipped"] = py::cast(skipped);
  out["period"] = comparison.period;
  py::dict runs;
  for (auto& run : comparison.runs) {
    py::dict one;
    one["meta"] = json_to_python(run_record(run.scene, run.output));
    one["termination"] = to_string(run.output.termination);
    one["events"] = event_array(run.output.events, run.output.event_columns, run.scene);
    runs[py::str(run.model)] = one;
  }
  out["runs"] = runs;
  return out;
}

// Work against precision on one scene (the CLI's `bench` does this for its
// fixed cases): each method at each rtol (atol = atol_ratio rtol), errors
// against bench_reference over reference_periods.
py::dict bench_binding(const Scene& scene, std::vector<std::string> methods,
                       const std::vector<double>& rtols, double atol_ratio, double periods,
                       double reference_periods, std::size_t max_reference_impacts,
                       int repetitions, py::object progress) {
  if (methods.empty())
    for (auto name : stepper_names)
      if (name != "exact" || has_closed_form(scene)) methods.emplace_back(name);
  for (const auto& method : methods) {
    bool known = false;
    for (auto name : stepper_names) known = known || name == method;
    if (!known || (method == "exact" && !has_closed_form(scene)))
      throw BadInput("methods", method, "not a stepper of this scene");
  }
  for (double rtol : rtols)
    if (!(rtol > 0.0 && rtol < 1.0)) throw BadInput("rtols", std::to_string(rtol), "expected 0 < rtol < 1");
  if (repetitions < 1) throw BadInput("repetitions", std::to_string(repetitions), "expected >= 1");
  const double forcing_period = scene.forcing_period();
  ProgressRelay relay(std::move(progress));
  py::dict out;
  std::vector<std::string> method_column;
  std::vector<double> rtol_column, atol_column, seconds, wall_seconds, rhs, steps, time_error,
      velocity_error;
  std::vector<std::uint64_t> impacts, compared;
  std::vector<std::string> termination;
  const std::size_t total = methods.size() * rtols.size();
  ReferenceImpacts reference;
  relay.run([&] {
    reference = bench_reference(scene, scene.number("t0") + reference_periods * forcing_period,
                                max_reference_impacts);
    std::size_t done = 0;
    for (const auto& method : methods)
      for (double rtol : rtols) {
        const WorkPrecisionPoint point = measure_point(scene, method, rtol, atol_ratio * rtol,
                                                       periods, repetitions, reference);
        method_column.push_back(method);
        rtol_column.push_back(point.rtol);
        atol_column.push_back(point.atol);
        impacts.push_back(point.impacts);
        seconds.push_back(point.seconds_per_impact);
        wall_seconds.push_back(point.wall_seconds_per_impact);
        rhs.push_back(point.rhs_per_impact);
        steps.push_back(point.steps_per_impact);
        time_error.push_back(point.errors.time);
        velocity_error.push_back(point.errors.velocity);
        compared.push_back(point.errors.compared);
        termination.push_back(point.termination);
        relay(static_cast<double>(++done) / static_cast<double>(total));
      }
    return 0;
  });
  out["method"] = py::cast(method_column);
  out["rtol"] = owning_array(std::move(rtol_column));
  out["atol"] = owning_array(std::move(atol_column));
  out["impacts"] = owning_array(std::move(impacts));
  out["seconds_per_impact"] = owning_array(std::move(seconds));
  out["wall_seconds_per_impact"] = owning_array(std::move(wall_seconds));
  out["rhs_per_impact"] = owning_array(std::move(rhs));
  out["steps_per_impact"] = owning_array(std::move(steps));
  out["impact_time_error"] = owning_array(std::move(time_error));
  out["impact_velocity_error"] = owning_array(std::move(velocity_error));
  out["impacts_compared"] = owning_array(std::move(compared));
  out["termination"] = py::cast(termination);
  out["reference_method"] = reference.method;
  out["reference_impacts"] = reference.impacts.size();
  return out;
}

// The columns of N-wide orbit states (q, qdot, state3 ... stateN) and of
// their N multipliers (multiplier1 ... multiplierN), as the CLI's continuation
// files name them; a missing component is NaN.
class OrbitColumns {
 public:
  explicit OrbitColumns(std::size_t dimension) : states_(dimension), multipliers_(dimension) {}

  void add_state(const OrbitPoint& state) {
    for (std::size_t k = 0; k < states_.size(); ++k)
      states_[k].push_back(k < state.size() ? state[k] : NAN);
  }
  void add_multipliers(const std::vector<std::complex<double>>& multipliers) {
    for (std::size_t k = 0; k < multipliers_.size(); ++k)
      multipliers_[k].push_back(k < multipliers.size() ? multipliers[k]
                                                       : std::complex<double>(NAN, NAN));
  }
  void put_states(py::dict& columns) {
    for (std::size_t k = 0; k < states_.size(); ++k)
      columns[py::str(k == 0 ? std::string("q") : k == 1 ? std::string("qdot")
                                                          : "state" + std::to_string(k + 1))] =
          owning_array(std::move(states_[k]));
  }
  void put_multipliers(py::dict& columns) {
    for (std::size_t k = 0; k < multipliers_.size(); ++k)
      columns[py::str("multiplier" + std::to_string(k + 1))] =
          owning_array(std::move(multipliers_[k]));
  }

 private:
  std::vector<std::vector<double>> states_;
  std::vector<std::vector<std::complex<double>>> multipliers_;
};

// One two-parameter curve as columns (the rows of curve.csv that carry its
// branch number); states and multipliers N = `dimension` wide.
py::dict curve_columns(const BranchCurve& curve, const std::string& parameter,
                       const std::string& parameter2, std::size_t dimension) {
  std::vector<double> p1, p2, graze_time;
  OrbitColumns orbit(dimension);
  std::vector<int> impacts, newton_iterations;
  for (const CurvePoint& p : curve.curve.curve) {
    p1.push_back(p.p1);
    p2.push_back(p.p2);
    orbit.add_state(p.state);
    orbit.add_multipliers(p.multipliers);
    graze_time.push_back(p.graze_time);
    impacts.push_back(p.impacts);
    newton_iterations.push_back(p.newton_iterations);
  }
  py::dict one;
  one["branch"] = curve.branch;
  one["period"] = curve.period;
  one["type"] = to_string(curve.curve.type);
  one["start"] = start_name(curve);
  one["stop_reason"] = to_string(curve.curve.stop_reason);
  one["stop_detail"] = curve.curve.stop_detail;
  one["map_evaluations"] = curve.curve.map_evaluations;
  one[py::str(parameter)] = owning_array(std::move(p1));
  one[py::str(parameter2)] = owning_array(std::move(p2));
  orbit.put_states(one);
  orbit.put_multipliers(one);
  one["graze_time"] = owning_array(std::move(graze_time));
  one["impacts"] = owning_array(std::move(impacts));
  one["newton_iterations"] = owning_array(std::move(newton_iterations));
  return one;
}

// The codimension-two points of the curves as columns (the rows of
// curve_points.csv, in the curves' order).
py::dict curve_point_columns(const std::vector<BranchCurve>& curves, const std::string& parameter,
                             const std::string& parameter2, std::size_t dimension) {
  std::vector<std::string> type, note;
  std::vector<double> p1, p2, error_estimate, graze_time;
  OrbitColumns orbit(dimension);
  std::vector<int> located, branch, period;
  for (const BranchCurve& curve : curves)
    for (const CodimensionTwoPoint& p : curve.curve.points) {
      type.emplace_back(to_string(p.type));
      p1.push_back(p.p1);
      p2.push_back(p.p2);
      orbit.add_state(p.state);
      orbit.add_multipliers(p.multipliers);
      error_estimate.push_back(p.error_estimate);
      located.push_back(p.located ? 1 : 0);
      graze_time.push_back(p.graze_time);
      branch.push_back(curve.branch);
      period.push_back(curve.period);
      note.push_back(p.note);
    }
  py::dict columns;
  columns["type"] = py::cast(type);
  columns[py::str(parameter)] = owning_array(std::move(p1));
  columns[py::str(parameter2)] = owning_array(std::move(p2));
  orbit.put_states(columns);
  orbit.put_multipliers(columns);
  columns["error_estimate"] = owning_array(std::move(error_estimate));
  columns["located"] = owning_array(std::move(located));
  columns["graze_time"] = owning_array(std::move(graze_time));
  columns["branch"] = owning_array(std::move(branch));
  columns["period"] = owning_array(std::move(period));
  columns["note"] = py::cast(note);
  return columns;
}

py::dict continue_binding(const Scene& scene, const ContinueOptions& options,
                          py::object progress) {
  const ContinuationJob job = continuation_job(options);
  const std::string& parameter = job.parameter;
  const std::string& parameter2 = job.second_parameter;
  const int period = job.period;
  ProgressRelay relay(std::move(progress));
  // the continuation reports no progress of its own: the check runs once after it;
  // with `all`, every orbit periodic --all finds at FROM, each continued
  std::optional<EveryOrbitContinuation> every;
  if (options.all) every = relay.run([&] { return continue_every_orbit(scene, job, options); });
  const ContinuationJobResult result =
      every ? every->continuation : relay.run([&] { return continue_orbit(scene, job); });
  relay(1.0);

  const std::size_t dimension = result.dimension;
  py::list branches;
  std::vector<std::string> type, note;
  std::vector<double> point_parameter, error_estimate, graze_time;
  OrbitColumns point_orbits(dimension);
  std::vector<int> point_period, point_branch, located, graze_witness;
  // the grazing points' normal forms: points.csv's columns and grazing.json's entries
  std::vector<std::string> scenario;
  std::vector<int> impacting_side, period_one_side;
  std::vector<double> impact_speed_coefficient, period_one_speed_slope;
  py::list grazing;
  int row = 0;
  for (std::size_t b = 0; b < result.branches.size(); ++b) {
    const ContinuedBranch& continued = result.branches[b];
    std::vector<double> value, min_impact_speed, min_flight_gap;
    OrbitColumns orbits(dimension);
    std::vector<int> impacts, contact_phases, stable, newton_iterations;
    for (const BranchPoint& p : continued.result.branch) {
      value.push_back(p.parameter);
      orbits.add_state(p.state);
      impacts.push_back(p.impacts);
      contact_phases.push_back(p.contact_phases);
      stable.push_back(p.stable ? 1 : 0);
      orbits.add_multipliers(p.multipliers);
      // branch.csv leaves an undefined speed or gap empty (NaN here)
      min_impact_speed.push_back(std::isfinite(p.min_impact_speed) ? p.min_impact_speed : NAN);
      min_flight_gap.push_back(std::isfinite(p.min_flight_gap) ? p.min_flight_gap : NAN);
      newton_iterations.push_back(p.newton_iterations);
    }
    py::dict one;
    one["period"] = continued.period;
    one["stop_reason"] = to_string(continued.result.stop_reason);
    one["stop_detail"] = continued.result.stop_detail;
    one["map_evaluations"] = continued.result.map_evaluations;
    one[py::str(parameter)] = owning_array(std::move(value));
    orbits.put_states(one);
    one["impacts"] = owning_array(std::move(impacts));
    one["contact_phases"] = owning_array(std::move(contact_phases));
    one["stable"] = owning_array(std::move(stable));
    orbits.put_multipliers(one);
    one["min_impact_speed"] = owning_array(std::move(min_impact_speed));
    one["min_flight_gap"] = owning_array(std::move(min_flight_gap));
    one["newton_iterations"] = owning_array(std::move(newton_iterations));
    if (every) one["orbit"] = every->branch_orbit[b];
    branches.append(one);
    for (const BifurcationPoint& p : continued.result.points) {
      type.emplace_back(type_name(p));
      point_parameter.push_back(p.parameter);
      point_orbits.add_state(p.state);
      point_period.push_back(continued.period);
      point_branch.push_back(static_cast<int>(b));
      point_orbits.add_multipliers(p.multipliers);
      error_estimate.push_back(p.error_estimate);
      located.push_back(p.located ? 1 : 0);
      graze_time.push_back(p.graze_time);
      graze_witness.push_back(p.graze_witness);
      note.push_back(p.note);
      const bool formed = p.normal_form && p.normal_form->available;
      scenario.push_back(p.type != BifurcationType::grazing ? ""
                         : formed ? std::string(to_string(p.normal_form->scenario))
                                  : "unavailable");
      impacting_side.push_back(formed ? p.normal_form->impacting_side : 0);
      period_one_side.push_back(formed ? p.normal_form->period_one_side : 0);
      impact_speed_coefficient.push_back(formed ? p.normal_form->root_coefficient : NAN);
      period_one_speed_slope.push_back(formed ? p.normal_form->period_one_slope : NAN);
      if (p.type == BifurcationType::grazing)
        grazing.append(json_to_python(
            grazing_record(p, parameter, row, static_cast<int>(b), continued.period)));
      ++row;
    }
  }
  py::dict points;
  points["type"] = py::cast(type);
  points[py::str(parameter)] = owning_array(std::move(point_parameter));
  point_orbits.put_states(points);
  points["period"] = owning_array(std::move(point_period));
  points["branch"] = owning_array(std::move(point_branch));
  point_orbits.put_multipliers(points);
  points["error_estimate"] = owning_array(std::move(error_estimate));
  points["located"] = owning_array(std::move(located));
  points["graze_time"] = owning_array(std::move(graze_time));
  points["graze_witness"] = owning_array(std::move(graze_witness));
  points["note"] = py::cast(note);
  points["scenario"] = py::cast(scenario);
  points["impacting_side"] = owning_array(std::move(impacting_side));
  points["impact_speed_coefficient"] = owning_array(std::move(impact_speed_coefficient));
  points["period_one_speed_slope"] = owning_array(std::move(period_one_speed_slope));
  points["period_one_side"] = owning_array(std::move(period_one_side));
  py::dict out;
  out["parameter"] = parameter;
  out["available"] = result.available;
  out["note"] = result.note;
  out["branches"] = branches;
  out["points"] = points;
  out["grazing"] = grazing;
  if (every) {
    const nlohmann::json found = periodic_orbits_record(scene, every->orbits);
    out["orbits"] = json_to_python(found["orbits"]);
    out["not_continued"] = py::cast(every->not_continued);
  }
  // a component held at its start value, as continuation.json's (index from 1)
  if (result.neutral) {
    py::dict neutral;
    neutral["index"] = result.neutral->index + 1;
    neutral["value"] = result.neutral->value;
    out["neutral_component"] = neutral;
  } else {
    out["neutral_component"] = py::none();
  }
  if (!parameter2.empty()) {
    // the first branch's curve, then each doubled branch's (switch), as the
    // CLI's curve.csv orders them
    std::vector<BranchCurve> followed;
    if (result.has_curve) followed.push_back({0, period, true, result.curve, result.curve_note});
    for (const BranchCurve& doubled : result.doubled_curves)
      if (doubled.has_curve) followed.push_back(doubled);
    for (const BranchCurve& switched : result.switched_curves)
      if (switched.has_curve) followed.push_back(switched);
    py::list curves;
    for (const BranchCurve& curve : followed)
      curves.append(curve_columns(curve, parameter, parameter2, dimension));
    out["curves"] = curves;
    out["curve_points"] = curve_point_columns(followed, parameter, parameter2, dimension);
    out["parameter2"] = parameter2;
    out["curve_note"] = result.has_curve ? std::string() : result.curve_note;
  }
  return out;
}

// The line of a BadInput with every option it names spelled as the Python
// keyword: the key is the option's own name already (api/job_options.hpp),
// and the options the reason names (`param`) lose their backquotes.
std::string keyword_message(const BadInput& bad) {
  const std::string what = bad.what();
  const std::string prefix = elide_value(bad.key()) + " = " + elide_value(bad.value()) + ": ";
  const auto keyword = [](std::string_view name) { return std::string(name); };
  if (!what.starts_with(prefix)) return spell_options(what, keyword);
  return prefix + spell_options(std::string_view(what).substr(prefix.size()), keyword);
}

// A job's option table (api/job_options.hpp) as a list of dicts, one per
// option: name, type, default (None where unset; an int for whole numbers, a
// tuple for a list of numbers), lower, upper, lower_open, unit, help (other
// options named as `name`), choices, front_ends, required, for_tests_only,
// excludes (the option it cannot be given with; "" for none).
py::list job_option_rows(const std::string& job) {
  static constexpr const char* type_names[] = {"number", "integer", "count", "text",
                                               "file", "flag", "text_list", "number_list"};
  static constexpr const char* front_end_names[] = {"both", "cli", "python"};
  py::list rows;
  for (const OptionSpec& spec : job_options(job)) {
    py::dict row;
    row["name"] = std::string(spec.name);
    row["type"] = type_names[static_cast<int>(spec.type)];
    const bool whole = spec.type == OptionType::integer || spec.type == OptionType::count;
    row["default"] = std::visit(
        [whole](const auto& value) -> py::object {
          using Value = std::decay_t<decltype(value)>;
          if constexpr (std::is_same_v<Value, Unset>) return py::none();
          else if constexpr (std::is_same_v<Value, double>)
            return whole ? py::object(py::int_(static_cast<long long>(value)))
                         : py::object(py::float_(value));
          else if constexpr (std::is_same_v<Value, std::string_view>)
            return py::str(std::string(value));
          else if constexpr (std::is_same_v<Value, std::vector<double>>)
            return py::tuple(py::cast(value));
          else
            return py::bool_(value);
        },
        spec.default_value);
    row["lower"] = spec.lower;
    row["upper"] = spec.upper;
    row["lower_open"] = spec.lower_open;
    row["unit"] = std::string(spec.unit);
    row["help"] = std::string(spec.help);
    py::list choices;
    for (std::string_view choice : spec.choices) choices.append(std::string(choice));
    row["choices"] = choices;
    row["front_ends"] = front_end_names[static_cast<int>(spec.front_ends)];
    row["required"] = spec.required;
    row["for_tests_only"] = spec.for_tests_only;
    row["excludes"] = std::string(spec.excludes);
    rows.append(row);
  }
  return rows;
}

py::list scene_keys(const Scene& scene) {
  py::list keys;
  for (const auto& spec : scene_schema(scene).keys) {
    py::dict entry;
    entry["key"] = std::string(spec.key);
    entry["unit"] = std::string(spec.unit);
    entry["help"] = std::string(spec.help);
    entry["is_text"] = spec.is_text;
    // the models that read the key, where the scene's models read different
    // keys (api/model_keys.hpp); empty where one model reads every key
    py::list read_by;
    for (auto model : models_reading(scene_schema(scene), spec))
      read_by.append(std::string(model));
    entry["read_by"] = read_by;
    if (spec.is_text) {
      py::list choices;
      for (auto choice : spec.choices) choices.append(std::string(choice));
      entry["choices"] = choices;
    } else {
      entry["lower"] = spec.lower;
      entry["upper"] = spec.upper;
      entry["lower_open"] = spec.lower_open;
      entry["upper_open"] = spec.upper_open;
    }
    keys.append(entry);
  }
  return keys;
}

py::dict scene_values(const Scene& scene) {
  py::dict values;
  for (const auto& [key, value] : scene.values) {
    if (const auto* number = std::get_if<double>(&value))
      values[py::str(key)] = *number;
    else
      values[py::str(key)] = std::get<std::string>(value);
  }
  return values;
}

}  // namespace

PYBIND11_MODULE(_impactlab, m) {
  m.doc() = "impactlab's scene API (use the package impactlab, not this module)";

  // bad input: ValueError whose message names the key and the value, as the CLI's line
  py::register_exception_translator([](std::exception_ptr pointer) {
    try {
      if (pointer) std::rethrow_exception(pointer);
    } catch (const BadInput& bad) {
      PyErr_SetString(PyExc_ValueError, keyword_message(bad).c_str());
    } catch (const OutputError& error) {
      // a file that cannot be written: the CLI's exit status 4
      PyErr_SetString(PyExc_OSError, error.what());
    }
  });

  py::class_<PendingRunRecord>(m, "PendingRunRecord").def("meta", &PendingRunRecord::meta);

  py::class_<Scene>(m, "Scene")
      .def_readonly("name", &Scene::name)
      .def_readonly("oscillator", &Scene::oscillator)
      .def_property_readonly(
          "main_coordinate",
          [](const Scene& scene) { return std::string(scene_schema(scene).main_coordinate); },
          "the coordinate q of the scene's sections and events (\"theta\", \"x\", \"y\")")
      .def("values", &scene_values)
      .def("keys", &scene_keys)
      .def("record", [](const Scene& scene) { return json_to_python(scene_record(scene)); })
      .def("copy", [](const Scene& scene) { return Scene(scene); })
      .def(
          "to_toml", [](const Scene& scene) { return scene_file_text(scene, scene_schema(scene)); },
          "the scene file that gives this scene again (every key with its value)")
      .def(
          "save",
          [](const Scene& scene, const std::filesystem::path& path) {
            save_scene_file(scene, scene_schema(scene), path);
          },
          py::arg("path"), "writes to_toml() to path, whole or not at all (OSError)");

  m.def("builtin_scene_names", [] {
    std::vector<std::string> names;
    for (const auto& builtin : builtin_scenes()) names.emplace_back(builtin.name);
    return names;
  });
  m.def("load_scene", [](const std::string& name) { return load_scene(name); });
  m.def("apply_override", [](Scene& scene, const std::string& assignment) {
    apply_override(scene, assignment);
  });
  m.def("unread_key_warnings", [](const Scene& scene, const std::vector<std::string>& keys) {
    return unread_key_warnings(scene, scene_schema(scene), keys);
  });
  m.def("simulate", &simulate_binding);
  m.def("poincare", &poincare_binding);
  m.def("sweep", &sweep_binding);
  m.def("basins", &basins_binding);
  m.def("attractors",
        [](const Scene& scene, const std::string& param, int samples,
           const std::vector<std::string>& box, std::uint64_t seed, const std::string& section,
           std::optional<double> transient, double max_transient,
           std::uint64_t transient_impacts, std::uint64_t points, bool lyapunov,
           double period_tolerance, int max_period, double attractor_tolerance,
           double match_tolerance, int threads, const std::string& batch, py::object progress) {
          return attractors_binding(
              scene,
              AttractorsArguments{param, samples, box, seed, section, transient, max_transient,
                                  transient_impacts, points, lyapunov, period_tolerance,
                                  max_period, attractor_tolerance, match_tolerance, threads,
                                  batch},
              std::move(progress));
        });
  m.def("periodic", &periodic_binding);
  m.def("periodic_orbits", &periodic_orbits_binding);
  m.def("compare", &compare_binding);
  m.def("bench", &bench_binding);
  m.def("continue_", [](const Scene& scene, const std::string& param, const std::string& param2,
                        const std::string& curve, int period, const std::string& section,
                        bool switch_doubling, const std::vector<double>& start, double transient,
                        int max_points, double tolerance, double max_step, bool all, int starts,
                        const std::vector<std::string>& box, std::uint64_t seed,
                        bool no_normal_forms, py::object progress) {
    ContinueOptions options;
    options.no_normal_forms = no_normal_forms;
    options.param = param;
    options.param2 = param2;
    options.curve = curve;
    options.period = period;
    options.section = section;
    options.switch_doubling = switch_doubling;
    options.start = start;
    options.transient = transient;
    options.max_points = max_points;
    options.tolerance = tolerance;
    options.max_step = max_step;
    options.all = all;
    options.starts = starts;
    options.box = box;
    options.seed = seed;
    return continue_binding(scene, options, std::move(progress));
  });
  m.def("job_names", [] {
    std::vector<std::string> names;
    for (std::string_view job : job_names()) names.emplace_back(job);
    return names;
  });
  m.def("job_options", &job_option_rows);
  m.attr("version") = IMPACTLAB_VERSION;
  m.def("event_kind_names", [] {
    std::vector<std::string> names;
    for (int kind = 0; kind <= static_cast<int>(EventKind::painleve); ++kind)
      names.emplace_back(to_string(static_cast<EventKind>(kind)));
    return names;
  });
}
