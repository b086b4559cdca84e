#include "pcsim/simulation/interrupt.hpp"

#include <csignal>
#include <ctime>

namespace pcsim::simulation {

namespace {

volatile sig_atomic_t g_signal = 0;
volatile sig_atomic_t g_first_at = 0;  // monotonic time of the first signal [s]
struct sigaction g_previous_int, g_previous_term;
int g_depth = 0;  // GracefulStops alive: a nested one (a run in an MPI sweep) keeps the outer's

// A second signal within this time of the first is the same request delivered
// twice: timeout(1) signals its child and then its whole process group, a
// terminal's Ctrl-C reaches mpirun (which forwards it) and the ranks.
constexpr long kRepeatWindowS = 1;

long monotonic_s() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe
  return static_cast<long>(now.tv_sec);
}

void on_signal(int signal_number) {
  if (g_signal != 0) {
    if (monotonic_s() - g_first_at <= kRepeatWindowS) return;
    // A later one: as if this handler were not there.
    sigaction(signal_number, signal_number == SIGINT ? &g_previous_int : &g_previous_term, nullptr);
    raise(signal_number);  // delivered when this handler returns
    return;
  }
  g_first_at = static_cast<sig_atomic_t>(monotonic_s());
  g_signal = signal_number;
}

void install(int signal_number, struct sigaction& previous) {
  sigaction(signal_number, nullptr, &previous);
  if (previous.sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaddset(&action.sa_mask, SIGINT);
  sigaddset(&action.sa_mask, SIGTERM);
  sigaction(signal_number, &action, nullptr);
}

}  // namespace

GracefulStop::GracefulStop() {
  if (g_depth++ > 0) return;  // the outer one's handlers and signal stay
  g_signal = 0;
  install(SIGINT, g_previous_int);
  install(SIGTERM, g_previous_term);
}

GracefulStop::~GracefulStop() {
  if (--g_depth > 0) return;
  if (g_previous_int.sa_handler != SIG_IGN) sigaction(SIGINT, &g_previous_int, nullptr);
  if (g_previous_term.sa_handler != SIG_IGN) sigaction(SIGTERM, &g_previous_term, nullptr);
}

int GracefulStop::local_signal() const {
  return g_signal;
}

int GracefulStop::agreed_signal(MPI_Comm comm) const {
  int mine = g_signal, agreed = 0;
  MPI_Allreduce(&mine, &agreed, 1, MPI_INT, MPI_MAX, comm);
  return agreed;
}

const char* signal_name(int signal_number) {
  switch (signal_number) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "a signal";
  }
}

}  // namespace pcsim::simulation
