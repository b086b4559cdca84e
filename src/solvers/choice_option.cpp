#include "choice_option.hpp"

#include <petscsys.h>

#include <algorithm>
#include <cstdio>

#include "pcsim/core/error.hpp"

namespace pcsim::solvers {

namespace {
PetscErrorCode read_string(MPI_Comm comm, const ChoiceOption& option, char* value,
                           std::size_t size) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, option.title, "pcsim");
  PetscCall(PetscOptionsString(option.name, option.help, "pcsim run", value, value, size, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

std::string read_choice_option(MPI_Comm comm, const ChoiceOption& option) {
  char value[32];
  std::snprintf(value, sizeof(value), "%s", option.value);
  PCSIM_PETSC(read_string(comm, option, value, sizeof(value)));
  const std::string choice = value;
  if (std::find(option.choices.begin(), option.choices.end(), choice) != option.choices.end())
    return choice;
  std::string list;
  for (std::size_t k = 0; k < option.choices.size(); ++k)
    list += (k == 0 ? "" : k + 1 == option.choices.size() ? " or " : ", ") + option.choices[k];
  throw InputError("command line", option.name, "must be " + list + " (got '" + choice + "')");
}

}  // namespace pcsim::solvers
