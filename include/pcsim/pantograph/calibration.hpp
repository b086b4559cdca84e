// Calibration of the DSA-380 parameter set to the natural frequencies of thesis Table 2.2
// (rigid model at the equilibrium under a 120 N downward force): Newton on
// log(kr, kl, l10 = l20, I7) with finite-difference sensitivities of the undamped
// frequencies, matched in ascending order.
#pragma once

#include <array>
#include <vector>

#include "pcsim/pantograph/dsa380.hpp"

namespace pcsim::pantograph {

inline constexpr std::array<double, 4> kThesisTable22Hz = {0.6551, 1.2439, 5.6231, 7.8705};

struct CalibrationResult {
  Dsa380Parameters params;
  std::vector<double> target_hz, obtained_hz;
  std::vector<int> dominant_dof;  // per mode, ascending frequency
  int iterations = 0;
};

// Undamped frequencies (ascending) and dominant coordinates at the equilibrium (F0, h0).
std::vector<double> dsa380_frequencies(const Dsa380Parameters& p, double contact_force,
                                       double working_height, std::vector<int>* dominant);

CalibrationResult calibrate_dsa380(Dsa380Parameters start, const std::array<double, 4>& target_hz,
                                   double contact_force, double working_height);

}  // namespace pcsim::pantograph
