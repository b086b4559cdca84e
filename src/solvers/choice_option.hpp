// A pcsim command-line option that names one of a few choices (-pcsim_path,
// -pcsim_step_solver): read from the options database, listed by -help,
// checked against the choices (InputError naming the option otherwise).
#pragma once

#include <mpi.h>

#include <string>
#include <vector>

namespace pcsim::solvers {

struct ChoiceOption {
  const char* name;   // "-pcsim_path"
  const char* title;  // the -help section, e.g. "pcsim dynamic run"
  const char* help;   // the option's -help text
  const char* value;  // the default
  std::vector<std::string> choices;
};

std::string read_choice_option(MPI_Comm comm, const ChoiceOption& option);

}  // namespace pcsim::solvers
