// Energy balance of a dynamic run (scene key output.energy): the system's
// energy E(t) (kinetic + strain + gravity + contact + pantograph), the work
// of the prescribed forces W_ext(t) (moving contact, uplift ramp) and the work
// of the dissipative forces W_diss(t) (Rayleigh damping, pantograph dampers,
// friction; <= 0), integrated from the terms' powers by the trapezoidal rule.
// A consistent integration keeps E(t) - E(0) = W_ext(t) + W_diss(t); the
// residual measures the integrator's numerical dissipation (HHT-α) or
// injection, and the switching error of contact and slack droppers.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pcsim::output {

struct EnergyHistory {
  std::vector<double> time, energy, power_external, power_dissipative;  // per step
};

struct EnergyBalance {
  std::vector<double> change, work_external, work_dissipated, residual;  // per step [J]
  double turnover = 0;       // max over t of |E - E0|, |W_ext|, |W_diss| [J]
  double max_residual = 0;   // max over t of |E - E0 - W_ext - W_diss| [J]
  double max_injection = 0;  // max over t of E - E0 - W_ext - W_diss, >= 0: energy the
                             // integration created (a negative residual it dissipated) [J]
  double final_residual = 0;
};

EnergyBalance energy_balance(const EnergyHistory& h);

// energy.h5 (datasets with units, the provenance as root attributes:
// provenance.hpp) in the file 'path'; returns the summary's "energy" entry.
nlohmann::json write_energy_results(const std::string& path, const EnergyHistory& h,
                                    const EnergyBalance& b,
                                    const nlohmann::json& provenance = nlohmann::json());

}  // namespace pcsim::output
