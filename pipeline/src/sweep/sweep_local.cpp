// `fragmpm sweep --jobs N`: N worker threads, each running one member at a time as child processes.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <thread>

#include "fragmpm/pipeline/sweep_runner.hpp"
#include "fragmpm/pipeline/sweep_schedule.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;

namespace {
double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

std::vector<std::size_t> unfinished_members(const SweepSpec& spec, const std::string& dir) {
  std::vector<std::size_t> todo;
  for (std::size_t m = 0; m < spec.members.size(); ++m) {
    if (!member_finished((fs::path(dir) / spec.members[m].name).string())) todo.push_back(m);
  }
  return todo;
}

SweepProgress::SweepProgress(std::size_t total, std::size_t already_done, int workers, bool enabled)
    : total_(total),
      done_(already_done),
      workers_(workers),
      enabled_(enabled),
      tty_(isatty(STDERR_FILENO)),
      start_(now_seconds()) {}

std::string SweepProgress::line(std::size_t running) const {
  char eta[48] = "ETA unknown";
  if (finished_now_ > 0) {
    // Mean wall time per member so far, spread over the workers.
    const double per_member = (now_seconds() - start_) / double(finished_now_);
    const double left = double(total_ - done_ - failed_);
    std::snprintf(eta, sizeof eta, "ETA %.0f s", per_member * left);
  }
  char text[160];
  std::snprintf(text, sizeof text, "sweep: %zu/%zu done, %zu failed, %zu running, %s", done_,
                total_, failed_, running, eta);
  (void)workers_;
  return text;
}

void SweepProgress::report(const std::string& name, const std::string& status, double wall_seconds,
                           std::size_t running) {
  if (status == "done") ++done_;
  if (status == "failed") ++failed_;
  if (status == "done" || status == "failed") ++finished_now_;
  if (!enabled_) return;
  std::fprintf(stderr, "%smember %s %s (%.1f s); %s\n", tty_ && shown_ ? "\r\033[K" : "",
               name.c_str(), status.c_str(), wall_seconds, line(running).c_str());
  shown_ = false;
}

void SweepProgress::refresh(std::size_t running) {
  if (!enabled_ || !tty_) return;
  std::fprintf(stderr, "\r\033[K%s", line(running).c_str());
  shown_ = true;
}

SweepProgress::~SweepProgress() {
  if (shown_) std::fprintf(stderr, "\n");
}

SweepTally run_sweep_local(const SweepSpec& spec, const std::vector<std::size_t>& todo,
                           const SweepRunOptions& options) {
  SweepTally tally;
  tally.total = spec.members.size();
  tally.skipped = tally.total - todo.size();
  const int workers = std::max(1, std::min<int>(options.jobs, static_cast<int>(todo.size())));
  SweepProgress progress(tally.total, tally.skipped, workers, options.progress);
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::condition_variable changed;
  std::size_t running = 0;
  const std::string exe = self_executable();

  auto work = [&] {
    for (;;) {
      if (stop_requested()) return;
      const std::size_t k = next.fetch_add(1);
      if (k >= todo.size()) return;
      const SweepMember& member = spec.members[todo[k]];
      {
        std::lock_guard lock(mutex);
        ++running;
      }
      MemberJob job{(fs::path(options.dir) / member.name).string(), exe, options.threads,
                    spec.analysis};
      const MemberStatus s = run_member(job);
      std::lock_guard lock(mutex);
      --running;
      if (s.status == "done") ++tally.done;
      if (s.status == "failed") ++tally.failed;
      if (s.status == "interrupted") ++tally.interrupted;
      progress.report(member.name, s.status, s.wall_seconds, running);
      changed.notify_all();
    }
  };
  std::vector<std::thread> threads;
  for (int w = 0; w < workers; ++w) threads.emplace_back(work);
  {
    std::unique_lock lock(mutex);
    while (tally.done + tally.failed + tally.interrupted < todo.size() && !stop_requested()) {
      progress.refresh(running);
      changed.wait_for(lock, std::chrono::seconds(1));
    }
  }
  for (std::thread& t : threads) t.join();
  write_manifest(spec, options.dir);
  return tally;
}

}  // namespace fragmpm::pipeline
