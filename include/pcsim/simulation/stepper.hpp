// A run advanced step by step by its caller: the building block of
// co-simulation and hardware-in-the-loop (the Python API's pcsim.Simulation,
// docs/python.md). The same set-up as simulation::run() (static
// configuration, catenary model, coupled system, static start, the HHT
// solver with the options database's numerics), then:
//   advance(n)  n time steps (TSSolve continued: the steps equal those of
//               an uninterrupted run of the scene, bit for bit on one rank);
//   reading()   time, and per pantograph the contact force, the contact
//               point's station and the head's height, on every rank;
//   set_head_force(p, f)  a vertical force on pantograph p's head from the
//               next step on (assembly/prescribed_forces.hpp);
//   set_base_motion(p, z, v, a)  pantograph p's base (the vehicle roof) at
//               height z [m, upwards] moving at v [m/s] with acceleration a
//               [m/s^2] from the next step on, held until set again (as the
//               scene's base_motion, which it replaces; a lumped model reads
//               z and v, a DSA-380 model's moving frame needs a too).
// Nothing is written: the caller keeps what it needs. A moving window (the
// scene's, or the modal level's on a long line) shifts as in a run, and the
// contact stations are the line's. No restart. Collective over ctx.comm;
// failures are exceptions on every rank.
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/context.hpp"

namespace pcsim::simulation {

struct StepReading {
  double t = 0;  // [s]
  long step = 0;
  // Per pantograph, in scene order.
  std::vector<double> contact_force;  // [N] on the head (sum over the contact wires)
  std::vector<double> contact_x;      // [m] station of the contact point
  std::vector<double> head_z;         // [m] height of the head's contact point
};

class Stepper {
 public:
  // The set-up's console lines unless ctx.quiet.
  Stepper(const Context& ctx, scene::RunScene& scene);
  ~Stepper();
  Stepper(const Stepper&) = delete;
  Stepper& operator=(const Stepper&) = delete;

  // Up to n steps, fewer at the scene's end time. Returns the steps taken.
  long advance(long n = 1);
  bool finished() const;
  double end_time() const;
  const StepReading& reading() const { return reading_; }
  std::vector<std::string> pantograph_names() const;
  void set_head_force(std::size_t pantograph, double force_N);
  double head_force(std::size_t pantograph) const;
  // acceleration_m_s2: NaN (not given) only for a lumped model.
  void set_base_motion(std::size_t pantograph, double displacement_m, double velocity_m_s,
                       double acceleration_m_s2 = std::numeric_limits<double>::quiet_NaN());

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  StepReading reading_;
  void read();  // reading_ at the TS's state (collective)
};

}  // namespace pcsim::simulation
