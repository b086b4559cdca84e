// Error types shared by all of pcsim.
//
// InputError: bad user input (file, key, reason). The app prints it once and
// exits non-zero; nothing is left in the output directory.
// InputWarning: input that is allowed but probably not what was meant (same
// three parts); the app prints it and goes on.
// SolverError: a numerical failure (PETSc error code, divergence).
// OutputError: a result file could not be written (full disk, no permission):
// the path and the OS error; the app exits with 5 and keeps the partial folder.
#pragma once

#include <petscsys.h>

#include <stdexcept>
#include <string>

namespace pcsim {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string key, std::string reason)
      : std::runtime_error(format(file, key, reason)),
        file_(std::move(file)),
        key_(std::move(key)),
        reason_(std::move(reason)) {}
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

  // "file: key 'a.b': reason" (the text of what()).
  static std::string format(const std::string& file, const std::string& key,
                            const std::string& reason) {
    std::string msg = file.empty() ? std::string("input") : file;
    if (!key.empty()) msg += ": key '" + key + "'";
    return msg + ": " + reason;
  }

 private:
  std::string file_, key_, reason_;
};

struct InputWarning {
  std::string file, key, reason;
  std::string message() const { return InputError::format(file, key, reason); }
};

class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class OutputError : public std::runtime_error {
 public:
  // "cannot write PATH: REASON"
  OutputError(std::string path, const std::string& reason)
      : std::runtime_error("cannot write " + path + ": " + reason),
        path_(std::move(path)),
        reason_(reason) {}
  const std::string& path() const { return path_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string path_, reason_;
};

// Why a write to 'path' failed: "No space left on device" when its file system
// is full, else the OS error 'saved_errno' (errno right after the failed
// call), else 'fallback'.
std::string write_failure_reason(const std::string& path, int saved_errno,
                                 const std::string& fallback = "the write failed");

[[noreturn]] void throw_petsc_error(PetscErrorCode code, const char* call, const char* file,
                                    int line);

}  // namespace pcsim

// Calls a PETSc function from C++ code and throws pcsim::SolverError on failure.
#define PCSIM_PETSC(call)                                                                \
  do {                                                                                   \
    PetscErrorCode pcsim_ierr_ = (call);                                                 \
    if (pcsim_ierr_) ::pcsim::throw_petsc_error(pcsim_ierr_, #call, __FILE__, __LINE__); \
  } while (0)

// Inside a PETSc callback (returns PetscErrorCode): turns a C++ exception into
// a PETSc error so that the solver stops cleanly.
#define PCSIM_CALLBACK_BEGIN try {
#define PCSIM_CALLBACK_END                                                   \
  }                                                                          \
  catch (const std::exception& e) {                                          \
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "pcsim callback: %s", e.what()); \
  }                                                                          \
  return 0;
