#include <impactlab/simulate/series_batch.hpp>

#include <array>
#include <exception>
#include <memory>
#include <stdexcept>
#include <utility>

#include <boost/context/fiber.hpp>
#include <boost/context/protected_fixedsize_stack.hpp>

#include <impactlab/integrate/series_tape.hpp>

namespace impactlab {

namespace {

namespace context = boost::context;

// a lane's stack (bytes): address space reserved once, pages committed as
// they are touched; the jobs run the event loop, sections, Lyapunov runs and
// the record writers (a few tens of kB deep), with a guard page below
constexpr std::size_t lane_stack_bytes = std::size_t{4} << 20;

// A lane: its fiber, the scheduler's fiber to switch back to, and its
// pending request.
class FiberLane final : public SeriesLane {
 public:
  FiberLane() = default;
  FiberLane(const FiberLane&) = delete;
  FiberLane& operator=(const FiberLane&) = delete;
  ~FiberLane() = default;

  void compute(SeriesRequest& request) override {
    request.tape = tape;
    request.rows = rows;
    pending = &request;
    scheduler = std::move(scheduler).resume();
    if (request.failure) std::rethrow_exception(request.failure);
  }

  context::fiber fiber;      // this lane's, resumed by the scheduler
  context::fiber scheduler;  // the scheduler's, resumed by this lane
  SeriesRequest* pending = nullptr;
  SeriesTape* tape = nullptr;      // this lane's
  SeriesLaneRows* rows = nullptr;  // the batch's
  bool finished = false;
  std::exception_ptr failure;
};

// Evaluates the requests of one kind together; where that throws, each one
// alone, its exception kept for its lane.
void evaluate_group(SeriesRequest* const* requests, int count) {
  try {
    requests[0]->evaluate(requests, count);
  } catch (...) {
    for (int i = 0; i < count; ++i) {
      try {
        requests[i]->evaluate(&requests[i], 1);
      } catch (...) {
        requests[i]->failure = std::current_exception();
      }
    }
  }
}

}  // namespace

BatchStatistics run_in_lanes(int width, FunctionRef<bool(SeriesLane& lane)> run_next_job) {
  if (width < 1 || width > max_series_lanes)
    throw std::invalid_argument("run_in_lanes: the width must be from 1 to max_series_lanes");
  std::array<FiberLane, max_series_lanes> lanes;
  const auto tapes = std::make_unique<SeriesTape[]>(static_cast<std::size_t>(width));
  const auto rows = std::make_unique_for_overwrite<SeriesLaneRows>();
  for (int i = 0; i < width; ++i) {
    FiberLane& lane = lanes[i];
    lane.tape = &tapes[static_cast<std::size_t>(i)];
    lane.rows = rows.get();
    lane.fiber = context::fiber(
        std::allocator_arg, context::protected_fixedsize_stack(lane_stack_bytes),
        [&lane, &run_next_job](context::fiber&& scheduler) {
          lane.scheduler = std::move(scheduler);
          try {
            while (run_next_job(lane)) {
            }
          } catch (const context::detail::forced_unwind&) {
            throw;
          } catch (...) {
            lane.failure = std::current_exception();
          }
          lane.finished = true;
          return std::move(lane.scheduler);
        });
  }
  BatchStatistics statistics;
  std::array<SeriesRequest*, max_series_lanes> waiting{};
  std::array<SeriesRequest*, max_series_lanes> group{};
  for (;;) {
    // every lane runs up to its next request or to its end
    int waiting_count = 0;
    for (int i = 0; i < width; ++i) {
      FiberLane& lane = lanes[i];
      if (lane.finished) continue;
      lane.pending = nullptr;
      lane.fiber = std::move(lane.fiber).resume();
      if (!lane.finished) waiting[waiting_count++] = lane.pending;
    }
    if (waiting_count == 0) break;
    // the requests of each kind (steppers of one type) together, in lane order
    for (int i = 0; i < waiting_count; ++i) {
      if (waiting[i] == nullptr) continue;
      const SeriesRequest::Evaluate kind = waiting[i]->evaluate;
      int count = 0;
      for (int j = i; j < waiting_count; ++j)
        if (waiting[j] != nullptr && waiting[j]->evaluate == kind) {
          group[count++] = waiting[j];
          waiting[j] = nullptr;
        }
      evaluate_group(group.data(), count);
      ++statistics.evaluations;
      statistics.lane_series += static_cast<std::uint64_t>(count);
      for (int j = 0; j < count; ++j)
        if (group[j]->in_pass) ++statistics.series_in_passes;
    }
  }
  for (int i = 0; i < width; ++i)
    if (lanes[i].failure) std::rethrow_exception(lanes[i].failure);
  return statistics;
}

}  // namespace impactlab
