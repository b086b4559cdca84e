#include "pcsim/pantograph/time_history.hpp"

namespace pcsim::pantograph {

std::vector<double> TimeHistory::energy_balance() const {
  std::vector<double> b(t.size());
  for (size_t k = 0; k < t.size(); ++k)
    b[k] = (kinetic[k] + potential[k]) - (kinetic[0] + potential[0]) - work_dissipative[k] -
           work_external[k];
  return b;
}

}  // namespace pcsim::pantograph
