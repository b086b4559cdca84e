#include "pcsim/simulation/auto_option.hpp"

#include <petscsys.h>

#include <string>

#include "pcsim/core/error.hpp"

namespace pcsim::simulation {

bool read_option_string(const char* title, const char* name, const char* help,
                        const char* shown_default, char* value, std::size_t size) {
  PetscBool given = PETSC_FALSE;
  // PETSc's macros return an error code: a function of their own.
  auto read = [&]() -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, title, "");
    PetscCall(PetscOptionsString(name, help, "", shown_default, value, size, &given));
    PetscOptionsEnd();
    PetscFunctionReturn(0);
  };
  PCSIM_PETSC(read());
  return given == PETSC_TRUE;
}

AutoChoice read_auto_option(const char* title, const char* name, const char* help) {
  char value[64] = "";
  const bool given = read_option_string(title, name, help, "auto", value, sizeof value);
  const std::string v = value;
  if (!given || v == "auto") return AutoChoice::automatic;
  if (v.empty() || v == "true" || v == "1" || v == "yes") return AutoChoice::on;
  if (v == "false" || v == "0" || v == "no") return AutoChoice::off;
  throw InputError("command line", name, "'" + v + "' is not auto, true or false");
}

}  // namespace pcsim::simulation
