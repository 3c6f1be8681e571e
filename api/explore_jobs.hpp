// The explorer's jobs: each view request runs on a thread of its own, so a
// slow one never blocks the page; a newer job of the same kind supersedes
// the older one, which is cancelled at its next progress report (the jobs'
// progress callbacks throw ExploreCancelled); at most `max_live` run at once,
// superseded ones included. A job's state, progress, partial results (the
// diagram's columns as they come) and result are read by polling.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

namespace impactlab {

// Thrown by a job's progress report once a newer job of its kind started.
struct ExploreCancelled {};

// Thrown by ExploreJobs::start for a request older than the kind's newest.
class ExploreSuperseded : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Thrown by ExploreJobs::start when max_live jobs are still running.
class ExploreBusy : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a running job sees of itself.
class ExploreJobControl {
 public:
  virtual ~ExploreJobControl() = default;
  // the fraction done (0..1); throws ExploreCancelled once superseded
  virtual void progress(double fraction) = 0;
  // one partial result (a diagram column), readable before the job ends
  virtual void add_item(const nlohmann::json& item) = 0;
};

class ExploreJobs {
 public:
  // the work of a job: its result as JSON; BadInput and other exceptions
  // become the job's error
  using Work = std::function<nlohmann::json(ExploreJobControl&)>;

  explicit ExploreJobs(int max_live, std::size_t kept_finished = 16);
  // cancels every job and waits for their threads
  ~ExploreJobs();
  ExploreJobs(const ExploreJobs&) = delete;
  ExploreJobs& operator=(const ExploreJobs&) = delete;

  // starts `work` as a job of `kind`, superseding that kind's running job;
  // returns its id. `sequence`: the count of `client`'s requests of the
  // kind (0: none), so that a request overtaken on its way by a newer one
  // from the same client (a page) is refused (ExploreSuperseded) rather
  // than run. Throws ExploreBusy when max_live jobs are running.
  std::uint64_t start(const std::string& kind, Work work, std::uint64_t sequence = 0,
                      const std::string& client = "");

  // the job's state: {id, kind, state (running, done, cancelled, failed),
  // progress, items from `first_item` on, item_count, result or error,
  // server_ms (the job's time so far)}; waits up to `wait` for it to change
  // while it runs. Null for an unknown (or long finished) id.
  nlohmann::json poll(std::uint64_t id, std::size_t first_item, std::chrono::milliseconds wait);

  // jobs running now, superseded ones included
  int live() const;

 private:
  struct Job;
  class Control;
  void run(const std::shared_ptr<Job>& job, const Work& work);
  // forgets finished jobs beyond the newest kept_finished; returns their threads to join
  std::vector<std::thread> prune_locked();

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  int max_live_;
  std::size_t kept_finished_;
  std::uint64_t next_id_ = 1;
  std::map<std::uint64_t, std::shared_ptr<Job>> jobs_;
  std::map<std::string, std::uint64_t> latest_of_kind_;
  std::map<std::string, std::uint64_t> latest_sequence_;
};

}  // namespace impactlab
