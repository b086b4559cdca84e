#include "pcsim/core/error.hpp"

namespace pcsim {

void throw_petsc_error(PetscErrorCode code, const char* call, const char* file, int line) {
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw SolverError(std::string("PETSc error ") + std::to_string(code) + " (" +
                    (text ? text : "unknown") + ") in " + call + " at " + file + ":" +
                    std::to_string(line));
}

}  // namespace pcsim
