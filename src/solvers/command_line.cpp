#include "pcsim/solvers/command_line.hpp"

#include <petscts.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "pcsim/core/error.hpp"
#include "pcsim/solvers/hht.hpp"

namespace pcsim::solvers {

namespace {

constexpr const char* kCommandLine = "command line";

[[noreturn]] void fail(const std::string& option, const std::string& reason) {
  throw InputError(kCommandLine, option, reason);
}

std::string in_quotes(const std::string& text) {
  return text.empty() ? std::string("nothing") : "'" + text + "'";
}

struct OptionTexts {
  char dt[256] = "", type[256] = "", alpha[256] = "", max_time[256] = "", max_steps[256] = "";
  PetscBool dt_set = PETSC_FALSE, type_set = PETSC_FALSE, alpha_set = PETSC_FALSE,
            max_time_set = PETSC_FALSE, max_steps_set = PETSC_FALSE;
};

// Read as text so that a malformed value is our input error, not PETSc's.
PetscErrorCode read_texts(MPI_Comm comm, OptionTexts* o) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "pcsim run: time integration (checked before the run)", "pcsim");
  PetscCall(PetscOptionsString("-ts_dt", "time step [s], > 0 (scene simulation.dt)", "pcsim run",
                               o->dt, o->dt, sizeof o->dt, &o->dt_set));
  PetscCall(PetscOptionsString("-ts_type",
                               "time integrator of the second-order system: hht (default) or "
                               "alpha2",
                               "pcsim run", "hht", o->type, sizeof o->type, &o->type_set));
  PetscCall(PetscOptionsString("-ts_hht_alpha", "HHT alpha in [0, 1/3] (default 0.1)", "pcsim run",
                               o->alpha, o->alpha, sizeof o->alpha, &o->alpha_set));
  PetscCall(PetscOptionsString(
      "-ts_max_time", "simulated time [s] to stop at, > 0: cuts the scene's run short", "pcsim run",
      o->max_time, o->max_time, sizeof o->max_time, &o->max_time_set));
  PetscCall(PetscOptionsString("-ts_max_steps", "time steps to stop after, >= 1", "pcsim run",
                               o->max_steps, o->max_steps, sizeof o->max_steps, &o->max_steps_set));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

// Types whose step solves M A + f(U, V) = 0 given by TSSetI2Function.
bool integrates_second_order(const std::string& type) {
  return type == kTSHHT || type == TSALPHA2;
}

}  // namespace

double parse_real_option(const std::string& option, const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size())
    fail(option, "must be a number (got " + in_quotes(text) + ")");
  if (errno == ERANGE || !std::isfinite(value))
    fail(option, "must be a finite number (got " + in_quotes(text) + ")");
  return value;
}

long parse_int_option(const std::string& option, const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
    fail(option, "must be an integer (got " + in_quotes(text) + ")");
  return value;
}

TimeIntegrationOptions read_time_integration_options(MPI_Comm comm) {
  OptionTexts texts;
  PCSIM_PETSC(read_texts(comm, &texts));
  TimeIntegrationOptions o;
  if (texts.dt_set) {
    const double dt = parse_real_option("-ts_dt", texts.dt);
    if (!(dt > 0))
      fail("-ts_dt", "must be a positive time step in seconds (got " + in_quotes(texts.dt) + ")");
    o.dt = dt;
  }
  if (texts.type_set) {
    o.ts_type = texts.type;
    register_hht_ts();
    PetscErrorCode (*create)(TS) = nullptr;
    PCSIM_PETSC(PetscFunctionListFind(TSList, o.ts_type.c_str(), &create));
    if (!create)
      fail("-ts_type", "unknown time integrator " + in_quotes(o.ts_type) + "; use hht or alpha2");
    if (!integrates_second_order(o.ts_type))
      fail("-ts_type", "'" + o.ts_type +
                           "' integrates first-order systems only; a run is second order (M A + "
                           "f(U, V) = 0, PETSc's I2 form): use hht (default) or alpha2");
  }
  if (texts.alpha_set) {
    const double alpha = parse_real_option("-ts_hht_alpha", texts.alpha);
    if (!(alpha >= 0 && alpha <= 1.0 / 3.0 + 1e-14))
      fail("-ts_hht_alpha", "must lie in [0, 1/3] (got " + in_quotes(texts.alpha) + ")");
    o.hht_alpha = alpha;
  }
  if (texts.max_time_set) {
    const double t = parse_real_option("-ts_max_time", texts.max_time);
    if (!(t > 0))
      fail("-ts_max_time",
           "must be a positive simulated time in seconds (got " + in_quotes(texts.max_time) + ")");
    o.max_time = t;
  }
  if (texts.max_steps_set) {
    const long n = parse_int_option("-ts_max_steps", texts.max_steps);
    if (n < 1)  // a run of no step has no state to write (and no acceleration)
      fail("-ts_max_steps",
           "must be a number of steps, 1 or more (got " + in_quotes(texts.max_steps) + ")");
    o.max_steps = n;
  }
  return o;
}

}  // namespace pcsim::solvers
