// Numeric options of the command line, checked before any work: a bad value
// is InputError("command line", option, reason) (exit 2), never a PETSc error
// in the middle of a run. Each reader declares its options in a
// PetscOptionsBegin block, so that -help lists them.
#pragma once

#include <mpi.h>

#include <optional>
#include <string>

namespace pcsim::solvers {

// The text of an option -> its value; InputError naming the option when the
// text is not a finite number (an integer for parse_int_option).
double parse_real_option(const std::string& option, const std::string& text);
long parse_int_option(const std::string& option, const std::string& text);

// Time integration of `pcsim run` (options database, no prefix):
//   -ts_dt         positive, finite;
//   -ts_type       a type that integrates a second-order (I2) system: hht, alpha2;
//   -ts_hht_alpha  in [0, 1/3];
//   -ts_max_time   positive, finite (at most the scene's run: read_run_inputs);
//   -ts_max_steps  a positive integer.
struct TimeIntegrationOptions {
  std::optional<double> dt;  // given by -ts_dt
  std::string ts_type = "hht";
  std::optional<double> hht_alpha;
  std::optional<double> max_time;  // -ts_max_time: cuts a run short
  std::optional<long> max_steps;   // -ts_max_steps: cuts a run short
};
TimeIntegrationOptions read_time_integration_options(MPI_Comm comm);

}  // namespace pcsim::solvers
