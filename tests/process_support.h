// Helpers for the fault tests: start the talus program as a child process (with a fault set up
// in the child: a file-size limit, another user), wait for a file to appear, collect the exit.
#pragma once

#include <algorithm>
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace talus::test {

struct Exit {
  int code = -1;   ///< exit status when it exited
  int signal = 0;  ///< the signal that ended it, else 0
  std::string log; ///< its stdout and stderr
  /// Lines of the log, without the empty ones.
  std::vector<std::string> lines() const {
    std::vector<std::string> out;
    std::istringstream in(log);
    for (std::string l; std::getline(in, l);)
      if (!l.empty()) out.push_back(l);
    return out;
  }
};

class TalusProcess {
public:
  /// Starts `talus args...`; `inChild` runs in the child before exec (limits, credentials).
  TalusProcess(const std::vector<std::string>& args, const std::string& logFile,
               const std::function<void()>& inChild = {})
      : log_(logFile) {
    pid_ = fork();
    if (pid_ == 0) {
      const int fd = open(logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(fd, 1), dup2(fd, 2);
      if (inChild) inChild();
      std::vector<char*> argv{const_cast<char*>(TALUS_BINARY)};
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      execv(TALUS_BINARY, argv.data());
      _exit(127);
    }
  }
  ~TalusProcess() {
    if (!done_) {
      kill(pid_, SIGKILL);
      wait();
    }
  }
  pid_t pid() const { return pid_; }
  void signal(int sig) const { kill(pid_, sig); }

  /// Waits until `path` exists; false when the process ended first or after `seconds`.
  bool waitForFile(const std::string& path, double seconds = 60) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (!std::filesystem::exists(path)) {
      int status;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        done_ = true;
        exit_ = decode(status);
        return false;
      }
      if (std::chrono::steady_clock::now() > end) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return true;
  }

  Exit wait() {
    if (!done_) {
      int status = 0;
      waitpid(pid_, &status, 0);
      done_ = true;
      exit_ = decode(status);
    }
    std::ifstream in(log_);
    std::stringstream s;
    s << in.rdbuf();
    exit_.log = s.str();
    return exit_;
  }

private:
  static Exit decode(int status) {
    Exit e;
    if (WIFEXITED(status)) e.code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
    return e;
  }
  pid_t pid_ = -1;
  std::string log_;
  bool done_ = false;
  Exit exit_;
};

/// Runs talus to its end.
inline Exit runTalusProcess(const std::vector<std::string>& args, const std::string& logFile,
                            const std::function<void()>& inChild = {}) {
  TalusProcess p(args, logFile, inChild);
  return p.wait();
}

/// Runs a shell command; returns its exit status, its output (stdout and stderr) in `out`.
inline int shell(const std::string& cmd, std::string& out) {
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  char buf[4096];
  out.clear();
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Files below `dir` (relative paths, sorted) whose name ends in `suffix`.
inline std::vector<std::string> filesEndingIn(const std::string& dir, const std::string& suffix) {
  std::vector<std::string> out;
  if (!std::filesystem::exists(dir)) return out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string p = e.path().string();
    if (p.size() >= suffix.size() && p.compare(p.size() - suffix.size(), suffix.size(), suffix) == 0)
      out.push_back(std::filesystem::relative(e.path(), dir).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The fault tests' scene: a rock sphere thrown at the floor of a 3 x 1 x 2 m box at dx 0.1 m,
/// run for `endTime` s, with `output` as the body of its [output] table.
inline std::string rockThrowScene(const std::string& endTime, const std::string& radius, const std::string& output) {
  return "\n[simulation]\ndx = 0.1\nend_time = " + endTime +
         "\n[domain]\nmin = [0, 0, 0]\nmax = [3, 1, 2]\nwalls = \"slip\"\n[[materials]]\nname = \"rock\"\n"
         "preset = \"rock\"\n[[bodies]]\nmaterial = \"rock\"\nshape = \"sphere\"\ncenter = [2.2, 0.5, 1.0]\nradius = " +
         radius + "\nvelocity = [-6, 0, -4]\n[output]\n" + output;
}

} // namespace talus::test
