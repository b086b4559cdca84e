// Child processes of pcsim: the postproc scripts (reports, plots) and the
// cases of a sweep. Called on rank 0 only (or by `pcsim sweep`, one rank).
#pragma once

#include <sys/types.h>

#include <functional>
#include <string>
#include <vector>

namespace pcsim::app {

// Starts argv[0] (a path; PATH is searched when it has no '/') with its
// stdout and stderr going to 'log_file' ("": inherited) and stdin closed.
// 'environment_drop': prefixes of environment variables the child does not
// get. Throws std::runtime_error if it cannot start.
pid_t start_process(const std::vector<std::string>& argv, const std::string& log_file,
                    const std::vector<std::string>& environment_drop = {});
// Waits for the process; its exit status, or 128 + signal if a signal ended it.
int wait_process(pid_t pid);
// Waits for any child; its pid, and its status in 'status'. A signal that
// interrupts the wait and for which 'stop' says true returns kWaitStopped.
// 'cpu_s' (if given): the CPU time (user + system) of the child and of its
// own waited-for children [s].
constexpr pid_t kWaitStopped = -2;
pid_t wait_any_process(int& status, const std::function<bool()>& stop = {},
                       double* cpu_s = nullptr);
// As wait_any_process, without waiting: 0 if no child has ended, -1 if none is left.
pid_t poll_any_process(int& status, double* cpu_s = nullptr);

// The CPU time (user + system) of this process so far [s].
double own_cpu_seconds();

// The last non-blank line of a text file ("" if none).
std::string last_line_of(const std::string& path);

// This executable (/proc/self/exe).
std::string own_executable();

// The Python interpreter for the postproc scripts: $PCSIM_PYTHON, else /usr/bin/python3.
std::string postproc_python();
// The script postproc/<name>: from $PCSIM_POSTPROC_DIR, the installed
// share/pcsim/postproc next to the executable, or the source tree.
std::string postproc_script(const std::string& name);

// Runs postproc/<script> with 'args'; "" on success, else why not (one line:
// the script's last line of output, or why it could not start).
// 'status': the script's exit status (kPostprocWriteFailed: it could not
// write its output, the last line of its log says why).
constexpr int kPostprocWriteFailed = 5;
std::string run_postproc(const std::string& script, const std::vector<std::string>& args,
                         int* status = nullptr);

}  // namespace pcsim::app
