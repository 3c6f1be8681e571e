#include <impactlab/simulate/series_batch.hpp>

#include <array>
#include <exception>
#include <memory>
#include <stdexcept>
#include <utility>

#include <boost/context/fiber.hpp>
#include <boost/context/preallocated.hpp>
#include <boost/context/protected_fixedsize_stack.hpp>

#if defined(__SANITIZE_ADDRESS__)
#define IMPACTLAB_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define IMPACTLAB_ADDRESS_SANITIZER 1
#endif
#endif
#if defined(IMPACTLAB_ADDRESS_SANITIZER)
#include <sanitizer/common_interface_defs.h>
#endif

#include <impactlab/integrate/series_tape.hpp>

namespace impactlab {

namespace {

namespace context = boost::context;

// a lane's stack (bytes): address space reserved once, pages committed as
// they are touched; the jobs run the event loop, sections, Lyapunov runs and
// the record writers (a few tens of kB deep), with a guard page below
constexpr std::size_t lane_stack_bytes = std::size_t{4} << 20;

// The bounds of a stack: its lowest address and its size (bytes).
struct StackBounds {
  const void* bottom = nullptr;
  std::size_t size = 0;
};

// AddressSanitizer keeps one stack per thread. Boost.Context's fibers switch
// stacks without telling it, and an exception thrown on a lane's stack then
// looks to it like a jump into another stack: it reports errors that are not
// there. These two calls tell it of each switch, on both sides: the first
// just before switching to the stack `to` (`fake_stack` null where the
// stack left will never run again), the second just after arriving, with
// the bounds of the stack left in `from` where it is wanted. Without the
// sanitizer they do nothing.
void before_stack_switch([[maybe_unused]] void** fake_stack, [[maybe_unused]] StackBounds to) {
#if defined(IMPACTLAB_ADDRESS_SANITIZER)
  __sanitizer_start_switch_fiber(fake_stack, to.bottom, to.size);
#endif
}

void after_stack_switch([[maybe_unused]] void* fake_stack, [[maybe_unused]] StackBounds* from) {
#if defined(IMPACTLAB_ADDRESS_SANITIZER)
  __sanitizer_finish_switch_fiber(fake_stack, from != nullptr ? &from->bottom : nullptr,
                                  from != nullptr ? &from->size : nullptr);
#endif
}

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
    request.row_pool = row_pool;
    pending = &request;
    before_stack_switch(&fake_stack, scheduler_stack);
    scheduler = std::move(scheduler).resume();
    after_stack_switch(fake_stack, nullptr);
    if (request.failure) std::rethrow_exception(request.failure);
  }

  context::fiber fiber;      // this lane's, resumed by the scheduler
  context::fiber scheduler;  // the scheduler's, resumed by this lane
  SeriesRequest* pending = nullptr;
  int rounds_deferred = 0;  // series rounds its pending request has waited for a partner
  SeriesTape* tape = nullptr;      // this lane's
  SeriesLaneRowsPool* row_pool = nullptr;  // the batch's
  bool finished = false;
  std::exception_ptr failure;
  StackBounds stack;            // this lane's
  StackBounds scheduler_stack;  // the scheduler's, learnt at the lane's start
  void* fake_stack = nullptr;   // the sanitizer's, kept while the lane waits
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

// A series request alone of its kind in a round, while other kinds share
// one, waits (its lane does not run) for up to `wait_rounds` series rounds
// in a row, for another lane to ask for a series of its kind. Its waiting[]
// entry is cleared.
void defer_lone_requests(SeriesRequest** waiting, const int* waiting_lane, int count,
                         FiberLane* lanes, int wait_rounds) {
  bool one_kind = true;  // the common case: nothing is alone
  for (int i = 1; i < count && one_kind; ++i)
    one_kind = waiting[i]->evaluate == waiting[0]->evaluate;
  if (one_kind) return;
  std::array<int, max_series_lanes> same_kind{};
  bool any_shared = false;
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j < count; ++j)
      if (waiting[j]->evaluate == waiting[i]->evaluate) ++same_kind[i];
    any_shared = any_shared || same_kind[i] > 1;
  }
  if (!any_shared) return;
  for (int i = 0; i < count; ++i) {
    FiberLane& lane = lanes[waiting_lane[i]];
    if (same_kind[i] == 1 && lane.rounds_deferred < wait_rounds) {
      ++lane.rounds_deferred;
      waiting[i] = nullptr;
    }
  }
}

}  // namespace

BatchStatistics run_in_lanes(int width, FunctionRef<bool(SeriesLane& lane)> run_next_job,
                             int lone_wait_rounds) {
  if (width < 1 || width > max_series_lanes)
    throw std::invalid_argument("run_in_lanes: the width must be from 1 to max_series_lanes");
  if (lone_wait_rounds < 0)
    throw std::invalid_argument("run_in_lanes: lone_wait_rounds must not be negative");
  std::array<FiberLane, max_series_lanes> lanes;
  const auto tapes = std::make_unique<SeriesTape[]>(static_cast<std::size_t>(width));
  const auto row_pool = std::make_unique<SeriesLaneRowsPool>();
  for (int i = 0; i < width; ++i) {
    FiberLane& lane = lanes[i];
    lane.tape = &tapes[static_cast<std::size_t>(i)];
    lane.row_pool = row_pool.get();
    context::protected_fixedsize_stack stack_allocator(lane_stack_bytes);
    const context::stack_context stack = stack_allocator.allocate();
    lane.stack = {static_cast<const char*>(stack.sp) - stack.size, stack.size};
    lane.fiber = context::fiber(
        std::allocator_arg, context::preallocated(stack.sp, stack.size, stack), stack_allocator,
        [&lane, &run_next_job](context::fiber&& scheduler) {
          after_stack_switch(nullptr, &lane.scheduler_stack);
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
          before_stack_switch(nullptr, lane.scheduler_stack);
          return std::move(lane.scheduler);
        });
  }
  BatchStatistics statistics;
  void* scheduler_fake_stack = nullptr;
  std::array<SeriesRequest*, max_series_lanes> waiting{};
  std::array<int, max_series_lanes> waiting_lane{};
  std::array<SeriesRequest*, max_series_lanes> group{};
  for (;;) {
    // every lane whose request was answered (or that has not started) runs
    // up to its next request or to its end
    int waiting_count = 0;
    bool any_before_series = false;
    for (int i = 0; i < width; ++i) {
      FiberLane& lane = lanes[i];
      if (lane.finished) continue;
      if (lane.pending == nullptr) {
        before_stack_switch(&scheduler_fake_stack, lane.stack);
        lane.fiber = std::move(lane.fiber).resume();
        after_stack_switch(scheduler_fake_stack, nullptr);
        if (lane.finished) continue;
      }
      waiting_lane[waiting_count] = i;
      waiting[waiting_count++] = lane.pending;
      any_before_series = any_before_series || lane.pending->before_series;
    }
    if (waiting_count == 0) break;
    // the requests that come before the series alone, while there are any
    // (their lanes run on to their next request in the next round); once
    // every lane waits for its series, the rows of the last series round
    // are free
    if (any_before_series) {
      for (int i = 0; i < waiting_count; ++i)
        if (!waiting[i]->before_series) waiting[i] = nullptr;
    } else {
      row_pool->start_round();
      defer_lone_requests(waiting.data(), waiting_lane.data(), waiting_count, lanes.data(),
                          lone_wait_rounds);
    }
    // the requests of each kind (steppers of one type) together, in lane order
    for (int i = 0; i < waiting_count; ++i) {
      if (waiting[i] == nullptr) continue;
      const SeriesRequest::Evaluate kind = waiting[i]->evaluate;
      int count = 0;
      for (int j = i; j < waiting_count; ++j)
        if (waiting[j] != nullptr && waiting[j]->evaluate == kind) {
          group[count++] = waiting[j];
          waiting[j] = nullptr;
          lanes[waiting_lane[j]].pending = nullptr;  // answered: runs on next round
          lanes[waiting_lane[j]].rounds_deferred = 0;
        }
      evaluate_group(group.data(), count);
      if (any_before_series) {
        ++statistics.early_evaluations;
        statistics.early_requests += static_cast<std::uint64_t>(count);
        continue;
      }
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
