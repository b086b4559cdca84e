// The wind's turbulence on the wires (docs/conditions.md, "Turbulence"): the
// drag of the fluctuations u' (along the mean wind) and w' (vertical),
// linearised about the mean wind (whose own drag is a dead load of the
// catenary, catenary/wind.hpp),
//   dq = (rho Cd d / 2) (|V_n| I + V_n V_n^T / |V_n|) P (u' e_V + w' e_z),
// P = I - t t^T the projection normal to the wire: across the track,
// rho Cd d V u' laterally and rho Cd d V w' / 2 vertically. A time-dependent
// load on the FE catenary's cable elements, u' and w' interpolated from the
// field's grid at the element's middle: residual only (no tangent), so the
// cheap path stays; its power is external work in the energy balance.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "pcsim/assembly/fe_catenary.hpp"
#include "pcsim/assembly/term.hpp"
#include "pcsim/catenary/wind.hpp"
#include "pcsim/catenary/wind_field.hpp"

namespace pcsim::assembly {

// A member's cross-section for drag: diameter d [m], drag coefficient Cd.
struct DragSection {
  double diameter = 0, drag_coefficient = 0;
};
DragSection wire_section(const catenary::Wire& wire);
DragSection bar_section(const catenary::BarElement& bar);

// A bar under the wind (droppers, stitch bars: a diameter, catenary/mesh.hpp),
// lumped half on each end node as its mean drag is (catenary::bar_drag): the
// aerodynamic damping (L/2) D P and the turbulence load (L/2) a, (L/2) b per
// unit u', w' on each end, the field taken at the bar's middle x.
struct WindBar {
  std::array<PetscInt, 6> idx{};  // the end nodes' translations (-1: fixed)
  Eigen::Matrix3d damping;        // [N s/m] on each end
  Eigen::Vector3d a, b;           // [N s/m] on each end per unit u', w'
  double x = 0;
};
std::vector<WindBar> wind_bars(const CatenarySystem& system);  // the rank's bars with a diameter

// The line's turbulence (u', w') over a mesh's stations
// (catenary::turbulence_grid): the line's own field, and a moving window's
// after each shift (follow: offset, the line's x at the window's x = 0;
// catenary::take_line_field). Every model of one scene draws the same field.
class LineTurbulence {
 public:
  explicit LineTurbulence(const catenary::CatenaryMesh& mesh);
  void follow(double offset);
  catenary::WindSeries u, w;

 private:
  std::unique_ptr<catenary::TurbulenceGenerator> u_line_, w_line_;
};

class WindTurbulence : public Term {
 public:
  explicit WindTurbulence(FECatenary& catenary);
  ~WindTurbulence() override;
  std::string name() const override { return "wind turbulence"; }
  TangentKind tangent_kind() const override { return TangentKind::constant; }
  bool adds_by_set_values() const override { return true; }
  void add_residual(const CoupledState& state, Vec F) override;
  TermPower power(const CoupledState& state) const override;

  const catenary::WindSeries& lateral() const { return field_.u; }
  const catenary::WindSeries& vertical() const { return field_.w; }
  // A moving window whose x = 0 is the line's x = offset: the field of the
  // line's stations over the window (the whole line's field there, bit for
  // bit; offsets never decrease).
  void follow(double offset);

 private:
  struct Element {
    std::array<PetscInt, 12> idx{};
    Eigen::Vector3d a, b;  // load per unstressed length per unit u', w' [N s/m^2]
    double x = 0, ref_length = 0, unstressed_length = 0;
  };
  void add_loads(double t, Vec F, double sign) const;
  std::vector<Element> elements_;
  std::vector<WindBar> bars_;
  LineTurbulence field_;
  mutable Vec work_ = nullptr;
};

// The aerodynamic damping of the wires in the mean wind: the quasi-steady
// drag of the relative velocity V - r', linearised about the mean wind,
// changes by -D P r' per unstressed length (D, P as above): a constant
// damper C = sum over the cable elements of (L0 / Lref) int S^T D P S dchi
// (D P is symmetric and positive semi-definite), F += C V, power -V.C V
// (dissipated). Across the track: rho Cd d V laterally, half that
// vertically, per unit velocity.
class AerodynamicDamping : public Term {
 public:
  explicit AerodynamicDamping(FECatenary& catenary);
  ~AerodynamicDamping() override;
  std::string name() const override { return "aerodynamic damping"; }
  TangentKind tangent_kind() const override { return TangentKind::constant; }
  std::vector<LinearPart> linear_parts() const override {
    return {{C_, 0.0, 1.0, 0.0, SUBSET_NONZERO_PATTERN}};
  }
  TermPower power(const CoupledState& state) const override;  // -V.C V
  Mat matrix() const { return C_; }

 private:
  Mat C_ = nullptr;
};

// The load per unstressed length per unit u' and w' on a wire of unit
// tangent t in the mean wind V (horizontal): the columns a, b above.
// D P of the aerodynamic damping (above) [N s/m^2].
Eigen::Matrix3d aerodynamic_damping(const DragSection& section, const Eigen::Vector3d& tangent,
                                    const Eigen::Vector3d& velocity, double air_density);

// The wires' aerodynamic damping matrix C (AerodynamicDamping, above) of
// the system's cable elements, in the catenary's pattern.
Mat aerodynamic_damping_matrix(const CatenarySystem& system);

// The turbulence load per unit u' (columns 0..n-1) and w' (n..2n-1) at each
// of the n stations, over the system's DOFs: the load WindTurbulence puts on
// the cable elements is L [u'(t); w'(t)] (the field linear between stations
// at each element's middle). The modal level projects it on its basis.
Mat turbulence_load_matrix(const CatenarySystem& system);

void turbulent_drag_gradients(const DragSection& section, const Eigen::Vector3d& tangent,
                              const Eigen::Vector3d& velocity, double air_density,
                              Eigen::Vector3d& a, Eigen::Vector3d& b);

}  // namespace pcsim::assembly
