// Runs an ensemble's members: each a normal `talus run` of the scene with its `--set`
// overrides, in its own folder DIR/member_NNN, as a separate process, several at a time. A
// re-run keeps the members whose summary.json says completed, resumes killed ones from their
// checkpoint (`talus run --resume`) and runs failed or missing ones anew.
//
// Members are started through a Launcher. The one here starts local processes; a later MPI
// launcher can hand each member to a rank group instead (the member's command line and folder
// are all it needs), and nothing else changes.
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace talus::ensemble {

enum class MemberState { Missing, Partial, Failed, Completed };

/// From DIR/member_NNN: summary.json with status "completed" (Completed), "interrupted" with a
/// checkpoint (Partial: stopped by SIGINT/SIGTERM) or another status (Failed); no summary but a
/// checkpoint (Partial: killed); else Missing.
MemberState memberState(const std::string& memberDir);
/// summary.json says "interrupted" (a member stopped by SIGINT or SIGTERM).
bool memberInterrupted(const std::string& memberDir);
/// wall_seconds from summary.json (NaN when absent).
double memberWallSeconds(const std::string& memberDir);

struct MemberJob {
  size_t index = 0;
  std::string dir;               ///< member folder
  std::vector<std::string> args; ///< talus arguments (run SCENE --out DIR ... --set ...)
};

/// Starts members and reports the next one to end (blocking).
class Launcher {
public:
  virtual ~Launcher() = default;
  virtual void start(const MemberJob& job) = 0;
  /// Waits for a started member to end: its index and exit status (128 + signal when killed).
  virtual std::pair<size_t, int> waitAny() = 0;
};

/// Local processes of this same program; stdout and stderr go to member_NNN/run.log.
class ProcessLauncher final : public Launcher {
public:
  explicit ProcessLauncher(std::string program);
  void start(const MemberJob& job) override;
  std::pair<size_t, int> waitAny() override;

private:
  std::string program_;
  std::vector<std::pair<int, size_t>> running_; ///< (pid, member)
};

struct RunReport {
  size_t completed = 0, failed = 0, skipped = 0, resumed = 0;
  double wallSeconds = 0;
  bool stopped = false; ///< `stop` answered true: members were left to run
};

/// Runs the jobs, `concurrent` at a time (>= 1); a member already completed is skipped, a killed
/// one resumed (`resumeArgs(job)` gives its command line). Progress counts members: a line on
/// a terminal, else one line per member ending. Once `stop` (when given) answers true, no member
/// is started and the running ones are waited for (a SIGINT from the terminal or a batch system's
/// SIGTERM reaches them too: they stop at a checkpoint). Returns the counts.
RunReport runMembers(const std::vector<MemberJob>& jobs, const std::function<std::vector<std::string>(const MemberJob&)>& resumeArgs,
                     size_t concurrent, Launcher& launcher, FILE* progress, const std::function<bool()>& stop = {});

/// A member's command line: `talus run SCENE --out DIR --threads T --quiet` with a `--set` for
/// each of `sets`, then each of `overrides`.
std::vector<std::string> memberArguments(const std::string& scene, const std::string& dir, int threads,
                                         const std::vector<std::string>& sets, const std::vector<std::string>& overrides);
/// The same member continued from its checkpoint: `--out` becomes `--resume`.
std::vector<std::string> resumeArguments(const MemberJob& job);

/// The path of the running program (/proc/self/exe).
std::string selfProgram();

} // namespace talus::ensemble
