// The event log: one record per discrete event of a run, in time order.
//
// The leading fields are the command-line contract's `events.csv` columns
// (t, kind, wall, q, qdot_before, qdot_after); the others carry the contact
// mechanics where a model computes them and are NaN where it does not.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include <impactlab/core/event_sink.hpp>

namespace impactlab {

enum class EventKind : std::uint8_t {
  impact,         // instantaneous impact, velocity reset by the impact law
  grazing,        // zero-velocity touch of a wall (double root of the gap)
  accumulation,   // limit point of a chattering (Zeno) sequence of impacts
  contact_start,  // sustained contact begins (after an accumulation)
  contact_end,    // release: the normal force reached zero
  slip_reversal,  // tangential velocity changed sign during contact
  painleve,       // contact problem inconsistent: run stopped (typed diagnostic)
};

constexpr std::string_view to_string(EventKind kind) {
  switch (kind) {
    case EventKind::impact: return "impact";
    case EventKind::grazing: return "grazing";
    case EventKind::accumulation: return "accumulation";
    case EventKind::contact_start: return "contact_start";
    case EventKind::contact_end: return "contact_end";
    case EventKind::slip_reversal: return "slip_reversal";
    case EventKind::painleve: return "painleve";
  }
  return "unknown";
}

struct EventRecord {
  static constexpr double not_computed = std::numeric_limits<double>::quiet_NaN();

  double t = 0.0;                      // event time (s)
  EventKind kind = EventKind::impact;  //
  int wall = 0;                        // +1 / -1 for the wall or table, 0 for none
  double q = 0.0;                      // main coordinate at the event (rad or m)
  double qdot_before = 0.0;            // its rate just before (rad/s or m/s)
  double qdot_after = 0.0;             // and just after
  double normal_impulse = not_computed;       // P_N (N s)
  double tangential_velocity = not_computed;  // γ_T at the event (m/s)
  double normal_force = not_computed;         // λ_N at the event (N)
  double friction_work = not_computed;        // work done by friction over the
                                              // contact phase that ends here (J)
  double tangential_velocity_after = not_computed;  // γ_T just after an impact (m/s)
  // an accumulation: the bound on the error of its time (s), from
  // contact/accumulation.hpp
  double accumulation_error = not_computed;
  // an impact whose contact point stops sliding (the stick case of a
  // Newton–Coulomb impulse, src/rigidbody/newton_coulomb_impulse.hpp)
  bool sticks = false;
};

// Counts every event, keeps the records unless told not to (a benchmark or a
// long sweep may only need the counts), and hands each to an event sink when
// one is given (a file written as the run goes). Reserve capacity up front to
// keep the event loop free of allocations. Also keeps the largest error bound
// of an accumulation time (s; 0 when none happened).
class EventLog {
 public:
  explicit EventLog(bool keep_records = true, EventSink* sink = nullptr)
      : keep_records_(keep_records), sink_(sink) {}

  void reserve(std::size_t n) { records_.reserve(n); }
  // forgets the records kept so far (the counts stay): a caller that reads
  // them chunk by chunk keeps its memory bounded
  void clear_records() { records_.clear(); }

  void record(const EventRecord& event) {
    ++counts_[static_cast<std::size_t>(event.kind)];
    if (event.kind == EventKind::impact && event.sticks) ++stick_impacts_;
    if (event.kind == EventKind::impact && std::fabs(event.qdot_before) < smallest_impact_speed_)
      smallest_impact_speed_ = std::fabs(event.qdot_before);
    if (event.kind == EventKind::accumulation && event.accumulation_error > largest_accumulation_error_)
      largest_accumulation_error_ = event.accumulation_error;
    if (keep_records_) records_.push_back(event);
    if (sink_) sink_->write(event);
    last_ = event;
  }

  [[nodiscard]] const std::vector<EventRecord>& records() const { return records_; }
  [[nodiscard]] std::uint64_t count(EventKind kind) const {
    return counts_[static_cast<std::size_t>(kind)];
  }
  // impacts whose impulse stuck (EventRecord::sticks)
  [[nodiscard]] std::uint64_t stick_impacts() const { return stick_impacts_; }
  [[nodiscard]] std::uint64_t total() const {
    std::uint64_t sum = 0;
    for (const auto n : counts_) sum += n;
    return sum;
  }
  // the last event recorded, if any
  [[nodiscard]] const EventRecord* last() const { return total() > 0 ? &last_ : nullptr; }
  [[nodiscard]] double largest_accumulation_error() const { return largest_accumulation_error_; }
  // the smallest |q̇| just before an impact (q per time unit; how near the
  // motion comes to grazing); +∞ before the first impact
  [[nodiscard]] double smallest_impact_speed() const { return smallest_impact_speed_; }

 private:
  static constexpr std::size_t kind_count = 7;
  bool keep_records_;
  EventSink* sink_;
  std::vector<EventRecord> records_;
  std::uint64_t counts_[kind_count] = {};
  std::uint64_t stick_impacts_ = 0;
  EventRecord last_{};
  double largest_accumulation_error_ = 0.0;
  double smallest_impact_speed_ = std::numeric_limits<double>::infinity();
};

}  // namespace impactlab
