// The signals a long run answers. SIGINT and SIGTERM ask it to stop after the step in progress:
// the run driver writes a checkpoint and summary.json ("status": "interrupted") and the program
// exits with 128 + the signal (130, 143); a second SIGINT or SIGTERM ends the process at once.
// SIGUSR1 asks for a checkpoint and the run goes on (batch systems send it before a job's time
// limit). The handlers only set flags, which the driver reads once per step: under MPI every rank
// will read its own flags at the same step and reduce them, so all ranks stop at the same step.
#pragma once

#include <string>

namespace talus {

/// Installs the handlers for its lifetime (and restores the previous ones after). One at a time.
class RunSignals {
public:
  /// `announce`: the first stop signal prints one line saying the run is stopping.
  explicit RunSignals(bool announce);
  ~RunSignals();
  RunSignals(const RunSignals&) = delete;
  RunSignals& operator=(const RunSignals&) = delete;
};

/// A line the first stop signal prints after its own (the run's step and last checkpoint, kept
/// current by the driver under mpirun, where the launcher's SIGTERM may follow a rank's death).
void setStopContext(const std::string& line);
/// SIGINT or SIGTERM once a stop was asked for, else 0.
int stopSignalReceived();
/// True once per SIGUSR1 received since the previous call.
bool takeCheckpointRequest();
/// "SIGTERM", "SIGINT", ... (or "signal N").
std::string signalName(int sig);

} // namespace talus
