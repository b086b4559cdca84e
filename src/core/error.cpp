#include "pcsim/core/error.hpp"

#include <sys/statvfs.h>

#include <cerrno>
#include <cstring>

namespace pcsim {

std::string write_failure_reason(const std::string& path, int saved_errno,
                                 const std::string& fallback) {
  const std::string::size_type slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  struct statvfs fs {};
  if (statvfs(dir.c_str(), &fs) == 0 && fs.f_bavail == 0) return std::strerror(ENOSPC);
  if (saved_errno != 0) return std::strerror(saved_errno);
  return fallback;
}

void throw_petsc_error(PetscErrorCode code, const char* call, const char* file, int line) {
  const char* text = nullptr;
  char* specific = nullptr;
  PetscErrorMessage(code, &text, &specific);
  std::string message =
      std::string("PETSc error ") + std::to_string(code) + " (" + (text ? text : "unknown") + ")";
  if (specific && *specific) message += ": " + std::string(specific);
  // The source file relative to the repository (no machine's path).
  std::string where = file;
  const auto src = where.rfind("/src/");
  if (src != std::string::npos) where = where.substr(src + 1);
  throw SolverError(message + " in " + call + " at " + where + ":" + std::to_string(line));
}

}  // namespace pcsim
