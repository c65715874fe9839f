#include "hazard/ensemble_runner.h"

#include "hazard/ensemble_plan.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <spawn.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace talus::ensemble {

namespace fs = std::filesystem;

namespace {

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string clock(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const long s = long(seconds + 0.5);
  char b[32];
  if (s >= 3600) std::snprintf(b, sizeof b, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else std::snprintf(b, sizeof b, "%ld:%02ld", s / 60, s % 60);
  return b;
}

} // namespace

bool memberInterrupted(const std::string& dir) {
  const fs::path summary = fs::path(dir) / "summary.json";
  return fs::exists(summary) && readFile(summary).find("\"status\": \"interrupted\"") != std::string::npos;
}

MemberState memberState(const std::string& dir) {
  const fs::path summary = fs::path(dir) / "summary.json";
  const bool checkpoint = fs::exists(fs::path(dir) / "checkpoint.h5");
  // SIGINT/SIGTERM (Ctrl-C reaches every member) leave "interrupted" and a checkpoint: resumable.
  if (memberInterrupted(dir)) return checkpoint ? MemberState::Partial : MemberState::Failed;
  if (fs::exists(summary))
    return readFile(summary).find("\"status\": \"completed\"") != std::string::npos ? MemberState::Completed
                                                                                    : MemberState::Failed;
  return checkpoint ? MemberState::Partial : MemberState::Missing;
}

double memberWallSeconds(const std::string& dir) {
  const std::string s = readFile(fs::path(dir) / "summary.json");
  const auto at = s.find("\"wall_seconds\":");
  return at == std::string::npos ? NAN : std::strtod(s.c_str() + at + 15, nullptr);
}

std::string selfProgram() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find the talus program (/proc/self/exe)");
  return p.string();
}

ProcessLauncher::ProcessLauncher(std::string program) : program_(std::move(program)) {}

void ProcessLauncher::start(const MemberJob& job) {
  fs::create_directories(job.dir);
  const std::string log = (fs::path(job.dir) / "run.log").string();
  std::vector<std::string> args{program_};
  args.insert(args.end(), job.args.begin(), job.args.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // posix_spawn, not fork: this process may hold TBB threads.
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, program_.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw std::runtime_error("cannot start " + program_ + ": " + std::strerror(rc));
  running_.emplace_back(int(pid), job.index);
}

std::pair<size_t, int> ProcessLauncher::waitAny() {
  if (running_.empty()) throw std::logic_error("waitAny: no member running");
  for (;;) {
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
    }
    for (size_t i = 0; i < running_.size(); ++i)
      if (running_[i].first == pid) {
        const size_t m = running_[i].second;
        running_.erase(running_.begin() + long(i));
        return {m, WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0)};
      }
  }
}

RunReport runMembers(const std::vector<MemberJob>& jobs,
                     const std::function<std::vector<std::string>(const MemberJob&)>& resumeArgs, size_t concurrent,
                     Launcher& launcher, FILE* progress, const std::function<bool()>& stop) {
  RunReport rep;
  const auto t0 = std::chrono::steady_clock::now();
  const bool tty = progress && isatty(fileno(progress));
  std::vector<const MemberJob*> todo;
  for (const auto& j : jobs) {
    const MemberState st = memberState(j.dir);
    if (st == MemberState::Completed) {
      ++rep.skipped, ++rep.completed;
      continue;
    }
    if (st == MemberState::Partial) ++rep.resumed;
    todo.push_back(&j);
  }
  if (progress && rep.skipped)
    std::fprintf(progress, "talus ensemble: %zu of %zu members completed before, kept\n", rep.skipped, jobs.size());
  if (progress && rep.resumed)
    std::fprintf(progress, "talus ensemble: %zu killed member(s) resume from their checkpoints\n", rep.resumed);
  const size_t total = jobs.size();
  size_t next = 0, running = 0, ran = 0;
  std::vector<size_t> resumedNow; // members started with --resume in this call
  double sumWall = 0;
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  auto bar = [&] {
    if (!tty) return;
    const size_t done = rep.completed + rep.failed;
    // ETA: the members still to run at the mean member time seen so far, spread over the slots.
    const double eta = ran ? sumWall / double(ran) * double(total - done) / double(concurrent) : NAN;
    std::fprintf(progress, "\r\033[Ktalus ensemble: %zu/%zu members done, %zu running, %zu failed | %s elapsed, ETA %s",
                 done, total, running, rep.failed, clock(elapsed()).c_str(), clock(eta).c_str());
    std::fflush(progress);
  };
  bar();
  auto stopping = [&] { return stop && stop(); };
  while ((next < todo.size() && !stopping()) || running > 0) {
    while (next < todo.size() && running < concurrent && !stopping()) {
      const MemberJob& j = *todo[next++];
      MemberJob run = j;
      if (memberState(j.dir) == MemberState::Partial) {
        run.args = resumeArgs(j);
        resumedNow.push_back(j.index);
      } else {
        std::error_code ec;
        fs::remove_all(j.dir, ec); // a failed or half-written member starts clean
      }
      launcher.start(run);
      ++running;
      bar();
    }
    if (running == 0) break; // stopped before another member started
    const auto [m, code] = launcher.waitAny();
    --running, ++ran;
    const MemberJob* j = nullptr;
    for (const auto* c : todo)
      if (c->index == m) j = c;
    const bool ok = code == 0 && memberState(j->dir) == MemberState::Completed;
    const double wall = memberWallSeconds(j->dir);
    if (std::isfinite(wall)) sumWall += wall;
    if (ok) ++rep.completed;
    else ++rep.failed;
    if (!ok && std::find(resumedNow.begin(), resumedNow.end(), m) != resumedNow.end() &&
        memberState(j->dir) == MemberState::Partial && !memberInterrupted(j->dir)) {
      // Its checkpoint did not take it to the end (and no signal stopped it): the next re-run
      // starts it anew instead.
      std::error_code ec;
      fs::remove(fs::path(j->dir) / "checkpoint.h5", ec);
    }
    if (progress && !tty)
      std::fprintf(progress, "talus ensemble: %s %s%s (%zu/%zu done)\n", memberName(m).c_str(),
                   ok ? "completed" : "failed", ok ? "" : (", exit " + std::to_string(code) + ", see " + j->dir + "/run.log").c_str(),
                   rep.completed + rep.failed, total);
    else if (progress && !ok) {
      std::fprintf(progress, "\r\033[Ktalus ensemble: %s failed (exit %d), see %s/run.log\n", memberName(m).c_str(), code,
                   j->dir.c_str());
    }
    bar();
  }
  if (tty) std::fprintf(progress, "\n");
  rep.stopped = stopping();
  rep.wallSeconds = elapsed();
  return rep;
}

std::vector<std::string> memberArguments(const std::string& scene, const std::string& dir, int threads,
                                         const std::vector<std::string>& sets, const std::vector<std::string>& overrides) {
  std::vector<std::string> args{"run", scene, "--out", dir, "--threads", std::to_string(threads), "--quiet"};
  for (const auto* list : {&sets, &overrides})
    for (const auto& s : *list) args.insert(args.end(), {"--set", s});
  return args;
}

std::vector<std::string> resumeArguments(const MemberJob& job) {
  std::vector<std::string> args = job.args;
  for (auto& a : args)
    if (a == "--out") a = "--resume";
  return args;
}

} // namespace talus::ensemble
