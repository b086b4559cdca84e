// Results of the studies of the pantograph alone (`pcsim pantograph`): summary.json and
//  - time:  time.h5  /<scheme>[_linear]/{t, q, qd, contact_height, contact_force,
//           energy/{kinetic, potential, work_dissipative, work_external, balance}, dof_names}
//  - frf:   frf.h5   /frequency_hz, /direct/{real, imag, abs}, /modal/... (symmetric models)
//  - sweep: sweep.h5 /frequency_hz, /nonlinear/A_<amplitude>, /linear/A_<amplitude>
// (modes and calibrate: summary.json only).
#pragma once

#include <string>

#include "pcsim/output/output_dir.hpp"
#include "pcsim/pantograph/study.hpp"

namespace pcsim::output {

// Writes the files of one study into out; returns the lines to print (one per result).
std::string write_pantograph_study(OutputDir& out, const std::string& scene_name,
                                   const pantograph::StudyScene& scene,
                                   const pantograph::StudyResult& result);

}  // namespace pcsim::output
