#include "output_guard.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pcsim/core/error.hpp"
#include "pcsim/output/output_dir.hpp"

namespace pcsim::output::guard {

namespace {

constexpr const char* kLockMagic = "pcsim output lock";

std::string manifest_path(const std::string& dir) {
  return dir + "/" + OutputDir::kManifestName;
}

}  // namespace

bool read_manifest(const std::string& dir, nlohmann::json& manifest) {
  std::ifstream in(manifest_path(dir));
  if (!in) return false;
  manifest = nlohmann::json::parse(in, nullptr, false);
  return manifest.is_object() && manifest.contains("pcsim_result");
}

void write_manifest(const std::string& dir, const nlohmann::json& manifest) {
  const std::string path = manifest_path(dir), tmp = path + ".tmp";
  errno = 0;
  bool ok = false;
  {
    std::ofstream out(tmp);
    out << manifest.dump(2) << "\n";
    out.close();
    ok = static_cast<bool>(out);
  }
  if (ok && std::rename(tmp.c_str(), path.c_str()) == 0) return;
  const int saved = errno;
  std::remove(tmp.c_str());
  throw OutputError(path, write_failure_reason(path, saved));
}

// Async-signal-safe (open, getdents64, close): used by the signal handler.
bool holds_only_manifest(const char* dir) {
  const int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return false;
  alignas(dirent64) char buffer[4096];
  bool manifest_seen = false, other_seen = false;
  for (;;) {
    const ssize_t n = getdents64(fd, buffer, sizeof buffer);
    if (n <= 0) {
      other_seen = other_seen || n < 0;
      break;
    }
    for (ssize_t offset = 0; offset < n;) {
      const auto* entry = reinterpret_cast<const dirent64*>(buffer + offset);
      offset += entry->d_reclen;
      const char* name = entry->d_name;
      if (!std::strcmp(name, ".") || !std::strcmp(name, "..")) continue;
      if (!std::strcmp(name, OutputDir::kManifestName))
        manifest_seen = true;
      else
        other_seen = true;
    }
  }
  close(fd);
  return manifest_seen && !other_seen;
}

bool holds_only_manifest(const std::string& dir) {
  return holds_only_manifest(dir.c_str());
}

bool holds_nothing_written(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::string tmp = OutputDir::kManifestName + std::string(".tmp");
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().filename() != tmp) return false;
  return !ec;
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

int acquire_lock(const std::string& path, const std::string& owner, std::string& why) {
  // A lock file deleted by its holder between our open() and flock() is not
  // the lock any more: check that the locked file is still the one at 'path'.
  for (int attempt = 0; attempt < 5; ++attempt) {
    const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      why = "cannot create the lock file " + path + ": " + std::strerror(errno);
      return -1;
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      if (errno != EWOULDBLOCK) {
        why = "cannot lock " + path + ": " + std::strerror(errno);
        close(fd);
        return -1;
      }
      char text[512] = {};
      const ssize_t n = pread(fd, text, sizeof text - 1, 0);
      std::string holder = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : "";
      while (!holder.empty() && holder.back() == '\n') holder.pop_back();
      const auto newline = holder.find('\n');
      if (newline != std::string::npos) holder = holder.substr(newline + 1);
      close(fd);
      why = "another pcsim run is writing this folder (" +
            (holder.empty() ? std::string("lock ") + path : holder) +
            "); wait for it to end or give another folder";
      return -1;
    }
    struct stat locked = {};
    struct stat named = {};
    if (fstat(fd, &locked) == 0 && stat(path.c_str(), &named) == 0 &&
        locked.st_dev == named.st_dev && locked.st_ino == named.st_ino) {
      // An existing file that is not a pcsim lock is not overwritten.
      const std::string magic = kLockMagic;
      std::string head(magic.size(), '\0');
      const ssize_t n = pread(fd, head.data(), head.size(), 0);
      if (n > 0 && head.compare(0, static_cast<std::size_t>(n), magic, 0,
                                static_cast<std::size_t>(n)) != 0) {
        close(fd);
        why = path + " exists and is not a pcsim lock file";
        return -1;
      }
      const std::string text = std::string(kLockMagic) + "\n" + owner + "\n";
      if (ftruncate(fd, 0) != 0 || pwrite(fd, text.data(), text.size(), 0) < 0) {
        close(fd);
        why = "cannot write the lock file " + path + ": " + std::strerror(errno);
        return -1;
      }
      return fd;
    }
    close(fd);
  }
  why = "cannot take the lock " + path + " (it keeps changing)";
  return -1;
}

void release_lock(int fd, const std::string& path) {
  if (fd < 0) return;
  unlink(path.c_str());  // while still locked: a waiting run re-checks the inode
  close(fd);
}

namespace {

// State of the signal handler: fixed buffers, set before it is installed.
char g_partial[PATH_MAX];
char g_manifest[PATH_MAX];
char g_lock[PATH_MAX];
struct sigaction g_previous_int, g_previous_term;
volatile sig_atomic_t g_armed = 0;

void on_interrupt(int signal_number) {
  if (g_armed) {
    if (holds_only_manifest(g_partial)) {
      unlink(g_manifest);
      rmdir(g_partial);
    }
    unlink(g_lock);
  }
  // End the process as the signal would have.
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  sigemptyset(&fallback.sa_mask);
  sigaction(signal_number, &fallback, nullptr);
  raise(signal_number);
}

void copy_path(char* to, const std::string& from) {
  std::snprintf(to, PATH_MAX, "%s", from.c_str());
}

void install(int signal_number, struct sigaction& previous) {
  sigaction(signal_number, nullptr, &previous);
  if (previous.sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  sigaddset(&action.sa_mask, SIGINT);
  sigaddset(&action.sa_mask, SIGTERM);
  sigaction(signal_number, &action, nullptr);
}

}  // namespace

bool arm_interrupt_cleanup(const std::string& partial, const std::string& lock) {
  if (g_armed || partial.size() + 32 >= PATH_MAX || lock.size() >= PATH_MAX) return false;
  copy_path(g_partial, partial);
  copy_path(g_manifest, manifest_path(partial));
  copy_path(g_lock, lock);
  g_armed = 1;
  install(SIGINT, g_previous_int);
  install(SIGTERM, g_previous_term);
  return true;
}

void disarm_interrupt_cleanup() {
  if (!g_armed) return;
  g_armed = 0;
  if (g_previous_int.sa_handler != SIG_IGN) sigaction(SIGINT, &g_previous_int, nullptr);
  if (g_previous_term.sa_handler != SIG_IGN) sigaction(SIGTERM, &g_previous_term, nullptr);
}

}  // namespace pcsim::output::guard
