// One sweep member = two child processes of this program (sweep_runner.hpp).
#include "fragmpm/pipeline/sweep_runner.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <limits>

#include "fragmpm/mpm/run_file_reader.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;

namespace {

std::atomic<bool> g_stop{false};
/// Children running now, so that the signal handler can pass the stop on (kill is
/// async-signal-safe; the slots are lock-free atomics).
std::array<std::atomic<pid_t>, 256> g_children{};

void on_stop(int) {
  g_stop.store(true);
  for (auto& c : g_children) {
    const pid_t pid = c.load();
    if (pid > 0) kill(pid, SIGTERM);
  }
}

/// Runs `argv` in `dir` with stdout and stderr appended to dir/log.txt; returns the exit code
/// (128 + signal when killed).
int run_child(const std::string& dir, const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const std::string log = (fs::path(dir) / "log.txt").string();
  {
    // The command line goes to the log first, so that a reader can repeat it.
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd >= 0) {
      std::string line = "$";
      for (const std::string& a : argv) line += " " + a;
      line += "\n";
      [[maybe_unused]] const ssize_t n = write(fd, line.data(), line.size());
      close(fd);
    }
  }
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) return 1;
  if (pid == 0) {
    // Child: only async-signal-safe calls until execv. A sweep killed outright (SIGKILL, which it
    // cannot pass on) takes its members with it, so that no orphan writes into a member folder
    // that the next sweep is running again. (The signal follows the forking thread, which waits
    // for this child.)
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(128 + SIGTERM);  // the sweep died before prctl
    if (chdir(dir.c_str()) != 0) _exit(127);
    const int fd = open("log.txt", O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
      close(fd);
    }
    execv(args[0], args.data());
    _exit(127);
  }
  std::atomic<pid_t>* slot = nullptr;
  for (auto& c : g_children) {
    pid_t expected = 0;
    if (c.compare_exchange_strong(expected, pid)) {
      slot = &c;
      break;
    }
  }
  if (g_stop.load()) kill(pid, SIGTERM);  // a stop that came before the slot was taken
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (slot) slot->store(0);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

void remove_outputs(const fs::path& dir) {
  std::error_code ec;
  for (const char* f : {"status.txt", "run.h5", "run.xmf", "log.txt"}) fs::remove(dir / f, ec);
  fs::remove_all(dir / "fragments", ec);
}

}  // namespace

std::string self_executable() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("fragmpm") : p.string();
}

void install_stop_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_stop;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

bool stop_requested() {
  return g_stop.load();
}

MemberStatus run_member(const MemberJob& job) {
  const fs::path dir(job.dir);
  remove_outputs(dir);
  const auto start = std::chrono::steady_clock::now();
  MemberStatus s;
  s.balance_error = std::numeric_limits<double>::quiet_NaN();
  s.stage = "run";
  s.exit_code = run_child(job.dir, {job.executable, "run", "scene.toml", "-o", "run.h5", "-q",
                                    "--threads", std::to_string(job.threads)});
  if (s.exit_code == 0 && !g_stop.load()) {
    s.stage = "analyze";
    std::vector<std::string> argv{job.executable,
                                  "analyze",
                                  "run.h5",
                                  "--csv-only",
                                  "--no-figures",
                                  "-o",
                                  "fragments",
                                  "--frame",
                                  "first,last",
                                  "--min-particles",
                                  std::to_string(job.analysis.min_particles),
                                  "--d-mask"};
    char d_mask[32];
    std::snprintf(d_mask, sizeof d_mask, "%.17g", job.analysis.d_mask);
    argv.push_back(d_mask);
    auto joined = [](const std::vector<std::string>& v) {
      std::string out;
      for (const std::string& x : v) out += (out.empty() ? "" : ",") + x;
      return out;
    };
    if (!job.analysis.at.empty()) argv.insert(argv.end(), {"--at", joined(job.analysis.at)});
    if (!job.analysis.at_displacement.empty())
      argv.insert(argv.end(), {"--at-displacement", joined(job.analysis.at_displacement)});
    s.exit_code = run_child(job.dir, argv);
  }
  s.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (g_stop.load()) {
    s.status = "interrupted";
    return s;
  }
  try {
    const mpm::RunFileReader file = mpm::RunFileReader::open((dir / "run.h5").string());
    const mpm::RunSeries series = file.read_series({"step", "balance_error"});
    if (series.has("step") && !series.column("step").empty())
      s.steps = static_cast<long long>(series.column("step").back());
    if (series.has("balance_error") && !series.column("balance_error").empty())
      s.balance_error = series.column("balance_error").back();
  } catch (const mpm::RunFileError&) {
    // No run file (bad input) or an unreadable one: the status says why through the exit code.
  }
  s.status = s.exit_code == 0 ? "done" : "failed";
  if (s.exit_code == 0) s.stage.clear();
  write_member_status(job.dir, s);
  return s;
}

}  // namespace fragmpm::pipeline
