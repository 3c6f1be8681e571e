#include <impactlab/api/explore_jobs.hpp>

#include <algorithm>
#include <atomic>

#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace {

// the shortest time between two answers of a poll of a running job
constexpr std::chrono::milliseconds poll_batch{100};

}  // namespace

struct ExploreJobs::Job {
  std::uint64_t id = 0;
  std::string kind;
  std::string state = "running";  // running, done, cancelled, failed
  double progress = 0.0;          // fraction done
  std::vector<nlohmann::json> items;
  nlohmann::json result;
  nlohmann::json error;
  std::atomic<bool> superseded{false};
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  double server_ms = 0.0;  // ms from start to end, once ended
  std::uint64_t version = 0;  // bumped on every change a poll waits for
  std::thread thread;
};

class ExploreJobs::Control final : public ExploreJobControl {
 public:
  Control(ExploreJobs& jobs, Job& job) : jobs_(jobs), job_(job) {}
  void progress(double fraction) override {
    if (job_.superseded.load()) throw ExploreCancelled{};
    {
      std::lock_guard lock(jobs_.mutex_);
      job_.progress = fraction;
      ++job_.version;
    }
    jobs_.changed_.notify_all();
  }
  void add_item(const nlohmann::json& item) override {
    {
      std::lock_guard lock(jobs_.mutex_);
      job_.items.push_back(item);
      ++job_.version;
    }
    jobs_.changed_.notify_all();
  }

 private:
  ExploreJobs& jobs_;
  Job& job_;
};

ExploreJobs::ExploreJobs(int max_live, std::size_t kept_finished)
    : max_live_(max_live), kept_finished_(kept_finished) {}

ExploreJobs::~ExploreJobs() {
  std::vector<std::thread> threads;
  {
    std::lock_guard lock(mutex_);
    for (auto& [id, job] : jobs_) {
      job->superseded = true;
      if (job->thread.joinable()) threads.push_back(std::move(job->thread));
    }
  }
  for (auto& thread : threads) thread.join();
}

int ExploreJobs::live() const {
  std::lock_guard lock(mutex_);
  int running = 0;
  for (const auto& [id, job] : jobs_) running += job->state == "running" ? 1 : 0;
  return running;
}

std::uint64_t ExploreJobs::start(const std::string& kind, Work work, std::uint64_t sequence,
                                 const std::string& client) {
  std::vector<std::thread> finished;
  std::uint64_t id = 0;
  {
    std::unique_lock lock(mutex_);
    const std::string ordered = kind + '\n' + client;
    if (sequence != 0 && sequence < latest_sequence_[ordered])
      throw ExploreSuperseded("a newer " + kind + " request came first");
    int running = 0;
    for (const auto& [other, job] : jobs_) running += job->state == "running" ? 1 : 0;
    if (running >= max_live_)
      throw ExploreBusy(std::to_string(running) + " jobs are running: try again when one ends");
    // the kind's older job stops at its next progress report
    if (const auto older = latest_of_kind_.find(kind); older != latest_of_kind_.end())
      if (const auto job = jobs_.find(older->second); job != jobs_.end())
        job->second->superseded = true;
    auto job = std::make_shared<Job>();
    job->id = id = next_id_++;
    job->kind = kind;
    jobs_[id] = job;
    latest_of_kind_[kind] = id;
    if (sequence != 0) latest_sequence_[ordered] = sequence;
    job->thread = std::thread([this, job, work = std::move(work)] { run(job, work); });
    finished = prune_locked();
  }
  for (auto& thread : finished) thread.join();
  return id;
}

void ExploreJobs::run(const std::shared_ptr<Job>& job, const Work& work) {
  Control control(*this, *job);
  std::string state = "done";
  nlohmann::json result, error;
  try {
    result = work(control);
    if (job->superseded) state = "cancelled";
  } catch (const ExploreCancelled&) {
    state = "cancelled";
  } catch (const BadInput& bad) {
    state = "failed";
    error = {{"key", bad.key()}, {"value", bad.value()}, {"message", bad.what()}};
  } catch (const std::exception& failure) {
    state = "failed";
    error = {{"key", ""}, {"value", ""}, {"message", failure.what()}};
  }
  {
    std::lock_guard lock(mutex_);
    job->state = state;
    job->result = std::move(result);
    job->error = std::move(error);
    if (state == "done") job->progress = 1.0;
    job->server_ms = std::chrono::duration<double, std::milli>(
                         std::chrono::steady_clock::now() - job->started).count();
    ++job->version;
  }
  changed_.notify_all();
}

std::vector<std::thread> ExploreJobs::prune_locked() {
  std::vector<std::uint64_t> finished;
  for (const auto& [id, job] : jobs_)
    if (job->state != "running") finished.push_back(id);
  std::vector<std::thread> threads;
  // the map is ordered by id: the oldest finished come first
  for (std::size_t k = 0; k + kept_finished_ < finished.size(); ++k) {
    auto& job = jobs_.at(finished[k]);
    if (job->thread.joinable()) threads.push_back(std::move(job->thread));
    jobs_.erase(finished[k]);
  }
  return threads;
}

nlohmann::json ExploreJobs::poll(std::uint64_t id, std::size_t first_item,
                                 std::chrono::milliseconds wait) {
  std::unique_lock lock(mutex_);
  const auto found = jobs_.find(id);
  if (found == jobs_.end()) return nullptr;
  const std::shared_ptr<Job> job = found->second;
  // wait for something new: an end, progress, or items beyond first_item
  const std::uint64_t seen = job->version;
  const bool nothing_new = job->state == "running" && job->items.size() <= first_item;
  if (nothing_new) {
    const auto deadline = std::chrono::steady_clock::now() + wait;
    changed_.wait_until(lock, deadline, [&] { return job->version != seen; });
    // progress of a job that runs on is handed out at most every
    // poll_batch, so that polling costs the job little of the CPU; its end
    // is handed out at once
    changed_.wait_until(lock, std::min(deadline, std::chrono::steady_clock::now() + poll_batch),
                        [&] { return job->state != "running"; });
  }
  nlohmann::json items = nlohmann::json::array();
  for (std::size_t k = first_item; k < job->items.size(); ++k) items.push_back(job->items[k]);
  const double elapsed =
      job->state == "running"
          ? std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                      job->started).count()
          : job->server_ms;
  nlohmann::json state = {{"id", job->id},
                          {"kind", job->kind},
                          {"state", job->state},
                          {"progress", job->progress},
                          {"items", items},
                          {"item_count", job->items.size()},
                          {"server_ms", elapsed}};
  if (job->state == "done") state["result"] = job->result;
  if (job->state == "failed") state["error"] = job->error;
  return state;
}

}  // namespace impactlab
