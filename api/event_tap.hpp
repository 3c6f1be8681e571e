// An event sink that shows each event of a run to a tally (a binding's derived
// quantities: the friction work, the sliding impacts) before passing it on to
// the request's own sink. The tally then sees every event whether or not the
// run keeps them (RunRequest::keep_events is false when the CLI streams
// events.csv), so meta.json's "derived" does not depend on how events are kept.
#pragma once

#include <functional>
#include <utility>

#include <impactlab/core/event_log.hpp>
#include <impactlab/core/event_sink.hpp>

namespace impactlab {

class EventTap final : public EventSink {
 public:
  EventTap(std::function<void(const EventRecord&)> tally, EventSink* next)
      : tally_(std::move(tally)), next_(next) {}

  void write(const EventRecord& event) override {
    tally_(event);
    if (next_) next_->write(event);
  }

 private:
  std::function<void(const EventRecord&)> tally_;
  EventSink* next_;
};

}  // namespace impactlab
