#include "processes.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

extern char** environ;

namespace pcsim::app {

namespace {

std::vector<std::string> child_environment(const std::vector<std::string>& drop) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    bool keep = true;
    for (const auto& prefix : drop) keep = keep && std::strncmp(*e, prefix.c_str(), prefix.size());
    if (keep) env.emplace_back(*e);
  }
  return env;
}

std::vector<char*> c_strings(std::vector<std::string>& words) {
  std::vector<char*> out;
  for (auto& w : words) out.push_back(w.data());
  out.push_back(nullptr);
  return out;
}

int status_of(int raw) {
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : WIFSIGNALED(raw) ? 128 + WTERMSIG(raw) : 4;
}

double cpu_seconds(const rusage& usage) {
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
         1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

}  // namespace

double own_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return cpu_seconds(usage);
}

std::string last_line_of(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  while (!last.empty() && last.back() == '\r') last.pop_back();
  return last;
}

pid_t start_process(const std::vector<std::string>& argv, const std::string& log_file,
                    const std::vector<std::string>& environment_drop) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  if (!log_file.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_file.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  std::vector<std::string> args = argv, env = child_environment(environment_drop);
  auto c_args = c_strings(args), c_env = c_strings(env);
  pid_t pid = -1;
  const int error =
      argv[0].find('/') == std::string::npos
          ? posix_spawnp(&pid, argv[0].c_str(), &actions, nullptr, c_args.data(), c_env.data())
          : posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, c_args.data(), c_env.data());
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(error));
  return pid;
}

int wait_process(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return 4;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 4;
}

pid_t wait_any_process(int& status, const std::function<bool()>& stop, double* cpu_s) {
  int raw = 0;
  rusage usage{};
  pid_t pid;
  while ((pid = wait4(-1, &raw, 0, &usage)) < 0) {
    if (errno != EINTR) return -1;
    if (stop && stop()) return kWaitStopped;
  }
  status = status_of(raw);
  if (cpu_s) *cpu_s = cpu_seconds(usage);
  return pid;
}

pid_t poll_any_process(int& status, double* cpu_s) {
  int raw = 0;
  rusage usage{};
  pid_t pid;
  while ((pid = wait4(-1, &raw, WNOHANG, &usage)) < 0)
    if (errno != EINTR) return -1;
  if (pid == 0) return 0;
  status = status_of(raw);
  if (cpu_s) *cpu_s = cpu_seconds(usage);
  return pid;
}

std::string own_executable() {
  std::error_code ec;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("pcsim") : path.string();
}

std::string postproc_python() {
  const char* python = std::getenv("PCSIM_PYTHON");
  return python && *python ? python : "/usr/bin/python3";
}

std::string postproc_script(const std::string& name) {
  namespace fs = std::filesystem;
  if (const char* dir = std::getenv("PCSIM_POSTPROC_DIR"); dir && *dir)
    return std::string(dir) + "/" + name;
  const fs::path installed =
      fs::path(own_executable()).parent_path().parent_path() / "share/pcsim/postproc" / name;
  std::error_code ec;
  if (fs::exists(installed, ec)) return installed.string();
  return std::string(PCSIM_SOURCE_DIR) + "/postproc/" + name;
}

std::string run_postproc(const std::string& script, const std::vector<std::string>& args,
                         int* status_out) {
  const std::string path = postproc_script(script);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return "no script " + path;
  char log[] = "/tmp/pcsim-postproc-XXXXXX";
  const int fd = mkstemp(log);
  if (fd < 0) return "cannot create a temporary file";
  close(fd);
  std::vector<std::string> argv = {postproc_python(), path};
  argv.insert(argv.end(), args.begin(), args.end());
  std::string why;
  try {
    const int status = wait_process(start_process(argv, log));
    if (status_out) *status_out = status;
    if (status != 0)
      why = script + " failed (exit " + std::to_string(status) + "): " + last_line_of(log);
  } catch (const std::exception& e) {
    why = e.what();
  }
  std::remove(log);
  return why;
}

}  // namespace pcsim::app
