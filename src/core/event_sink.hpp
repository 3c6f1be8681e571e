// Where the events of a run go as they happen, when they are not kept in
// memory: a file writer (io/output.hpp) streams them so that a run's memory
// does not grow with its length.
#pragma once

namespace impactlab {

struct EventRecord;  // core/event_log.hpp

// Receives every event record of a run, in time order, once. Called once per
// event from the event loop (not per step or right-hand-side evaluation).
class EventSink {
 public:
  virtual ~EventSink() = default;
  virtual void write(const EventRecord& event) = 0;
};

}  // namespace impactlab
