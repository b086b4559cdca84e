#include "pcsim/output/energy_results.hpp"

#include <algorithm>
#include <cmath>

#include "pcsim/output/h5_file.hpp"
#include "pcsim/output/provenance.hpp"

namespace pcsim::output {

EnergyBalance energy_balance(const EnergyHistory& h) {
  EnergyBalance b;
  const std::size_t n = h.time.size();
  double w_ext = 0, w_diss = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) {
      const double dt = h.time[i] - h.time[i - 1];
      w_ext += 0.5 * dt * (h.power_external[i] + h.power_external[i - 1]);
      w_diss += 0.5 * dt * (h.power_dissipative[i] + h.power_dissipative[i - 1]);
    }
    const double change = h.energy[i] - h.energy[0];
    b.change.push_back(change);
    b.work_external.push_back(w_ext);
    b.work_dissipated.push_back(w_diss);
    b.residual.push_back(change - w_ext - w_diss);
    b.turnover = std::max({b.turnover, std::abs(change), std::abs(w_ext), std::abs(w_diss)});
    b.max_residual = std::max(b.max_residual, std::abs(b.residual.back()));
    b.max_injection = std::max(b.max_injection, b.residual.back());
  }
  if (n > 0) b.final_residual = b.residual.back();
  return b;
}

nlohmann::json write_energy_results(const std::string& path, const EnergyHistory& h,
                                    const EnergyBalance& b, const nlohmann::json& provenance) {
  H5File h5(path);
  stamp_provenance(h5, provenance);
  h5.write("/time", h.time, {"s", "time of each step"});
  h5.write("/energy", h.energy,
           {"J", "energy of the system E(t): kinetic, strain, gravity, contact, pantograph"});
  h5.write("/energy_change", b.change, {"J", "E(t) - E(0)"});
  h5.write("/power_external", h.power_external,
           {"W", "power of the prescribed forces (moving contact, uplift ramp)"});
  h5.write("/power_dissipative", h.power_dissipative,
           {"W", "power of the dissipative forces (damping, friction), <= 0"});
  h5.write("/work_external", b.work_external, {"J", "W_ext(t): time integral of power_external"});
  h5.write("/work_dissipated", b.work_dissipated,
           {"J", "W_diss(t): time integral of power_dissipative, <= 0"});
  h5.write("/balance_residual", b.residual, {"J", "E(t) - E(0) - W_ext(t) - W_diss(t)"});
  nlohmann::json j;
  j["work_external_J"] = b.work_external.empty() ? 0.0 : b.work_external.back();
  j["work_dissipated_J"] = b.work_dissipated.empty() ? 0.0 : b.work_dissipated.back();
  j["energy_change_J"] = b.change.empty() ? 0.0 : b.change.back();
  j["turnover_J"] = b.turnover;
  j["max_balance_residual_J"] = b.max_residual;
  j["final_balance_residual_J"] = b.final_residual;
  j["max_energy_injection_J"] = b.max_injection;
  return j;
}

}  // namespace pcsim::output
