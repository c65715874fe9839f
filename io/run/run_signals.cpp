#include "io/run/run_signals.h"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <unistd.h>

namespace talus {

namespace {

// Lock-free atomics are safe in handlers; two signals may reach two threads at the same time.
static_assert(std::atomic<int>::is_always_lock_free);
std::atomic<int> gStops{0};
volatile std::sig_atomic_t gStop = 0;
volatile std::sig_atomic_t gCheckpoint = 0;
volatile std::sig_atomic_t gAnnounce = 0;
struct sigaction gPrevious[3];
constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGUSR1};
// The context line a stop prints (double-buffered: the driver writes one buffer while the
// handler may read the other).
char gContext[2][256] = {{0}, {0}};
std::atomic<int> gContextActive{0};

// Only async-signal-safe calls here: flags, write(2), sigaction, raise.
void onStop(int sig) {
  if (gStops.fetch_add(1) > 0) {
    // The second signal: the default action, i.e. the process ends now (by that signal).
    struct sigaction dfl{};
    dfl.sa_handler = SIG_DFL;
    sigaction(sig, &dfl, nullptr);
    raise(sig); // delivered when this handler returns
    return;
  }
  gStop = sig;
  if (gAnnounce) {
    static const char msg[] = "\ntalus: stopping after this step to write a checkpoint (signal again to stop at once)\n";
    [[maybe_unused]] const ssize_t w = write(STDERR_FILENO, msg, sizeof msg - 1);
    const char* context = gContext[gContextActive.load()];
    if (context[0]) [[maybe_unused]] const ssize_t w2 = write(STDERR_FILENO, context, strlen(context));
  }
}

void onCheckpoint(int) { gCheckpoint = 1; }

} // namespace

RunSignals::RunSignals(bool announce) {
  gStops = 0, gStop = 0, gCheckpoint = 0, gAnnounce = announce;
  gContext[0][0] = gContext[1][0] = 0;
  for (int i = 0; i < 3; ++i) {
    struct sigaction sa{};
    sa.sa_handler = kSignals[i] == SIGUSR1 ? onCheckpoint : onStop;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART; // a write interrupted by a signal continues instead of failing
    sigaction(kSignals[i], &sa, &gPrevious[i]);
  }
}

RunSignals::~RunSignals() {
  for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &gPrevious[i], nullptr);
}

void setStopContext(const std::string& line) {
  const int next = 1 - gContextActive.load();
  std::snprintf(gContext[next], sizeof gContext[next], "%s\n", line.c_str());
  gContextActive.store(next);
}

int stopSignalReceived() { return gStop; }

bool takeCheckpointRequest() {
  if (!gCheckpoint) return false;
  gCheckpoint = 0;
  return true;
}

std::string signalName(int sig) {
  switch (sig) {
  case SIGINT: return "SIGINT";
  case SIGTERM: return "SIGTERM";
  case SIGUSR1: return "SIGUSR1";
  default: return "signal " + std::to_string(sig);
  }
}

} // namespace talus
