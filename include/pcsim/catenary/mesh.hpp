// Catenary finite-element mesh: nodes, ANCF cable elements, bar elements,
// point masses, supports, and the targets of form-finding.
//
// Coordinates: x along the track, y lateral, z vertical (up); SI units.
// Every node carries 6 DOFs: position r = (x, y, z) and slope r' = dr/dchi,
// chi being the arc-length parameter of the design configuration (thesis
// eq. 3.2). Slope DOFs of nodes that belong to no cable element are not
// unknowns (the assembly fixes them).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "pcsim/catenary/track.hpp"
#include "pcsim/core/node_values.hpp"

namespace pcsim::catenary {

using pcsim::kNodeDofs;
using pcsim::positions_from_node_values;

struct Node {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // design position [m]
  Eigen::Vector3d slope = Eigen::Vector3d::Zero();     // design unit tangent (cable nodes)
  std::array<bool, kNodeDofs> fixed{};                 // DOF held at its design value
};

enum class WireKind { messenger, contact, stitch, other };

// Cable properties (thesis 3.1.1).
// Linear thermal expansion of copper and bronze wires (CuAg, CuMg, Bz II:
// 17e-6 /K), the default of a design's wires [1/K].
inline constexpr double kCopperThermalExpansion = 1.7e-5;

struct Wire {
  std::string name;
  WireKind kind = WireKind::other;
  double mass_per_length = 0;  // per unstressed length (the wire as bought) [kg/m]
  double EA = 0;               // axial stiffness [N]
  double EI = 0;               // bending stiffness [N m^2]
  double tension = 0;          // design tension [N] (form-finding target)
  std::vector<int> nodes;      // node indices in order along the wire
  std::vector<int> elements;   // cable element indices in order
  double thermal_expansion = kCopperThermalExpansion;  // [1/K] (last: aggregate order)
  // Wind (docs/conditions.md): outer diameter [m] and drag coefficient [1];
  // 0: the default of the wire's kind (wire_diameter, wire_drag_coefficient).
  double diameter = 0;
  double drag_coefficient = 0;
};

// Default diameters [m] of the EN 50318 reference line's wires: an AC-120
// grooved contact wire (13.2 mm) and a Bz 65 stranded messenger (10.5 mm);
// stitch wires Bz 35 (7.5 mm); another wire 10 mm (docs/conditions.md).
inline double default_wire_diameter(WireKind kind) {
  return kind == WireKind::contact     ? 0.0132
         : kind == WireKind::messenger ? 0.0105
         : kind == WireKind::stitch    ? 0.0075
                                       : 0.010;
}
// Default drag coefficients: a circular cylinder in the subcritical range
// (Re = V d / nu ~ 1e4-4e4 for 10-40 m/s): 1.0 for the smooth contact
// wire, 1.2 for stranded wires (docs/conditions.md).
inline double default_drag_coefficient(WireKind kind) {
  return kind == WireKind::contact ? 1.0 : 1.2;
}
inline double wire_diameter(const Wire& w) {
  return w.diameter > 0 ? w.diameter : default_wire_diameter(w.kind);
}
inline double wire_drag_coefficient(const Wire& w) {
  return w.drag_coefficient > 0 ? w.drag_coefficient : default_drag_coefficient(w.kind);
}

// Transverse wave speed sqrt(T / rho_T) of a wire at its design tension,
// rho_T = rho / (1 + T/EA) the mass per stretched length [m/s].
inline double wave_speed(const Wire& wire) {
  return std::sqrt(wire.tension * (1.0 + wire.tension / wire.EA) / wire.mass_per_length);
}

// ANCF cable element between nodes[0] and nodes[1].
struct CableElement {
  std::array<int, 2> nodes{};
  int wire = -1;
  double ref_length = 0;         // length of the chi parameter (design length) [m]
  double unstressed_length = 0;  // L0 [m]; strain is measured against it
  int tension_segment = -1;      // index into CatenaryMesh::tension_segments, or -1
  // Cross-section left (worn wire): EA and the mass scale with it, EI with its
  // square (a round section); 1 for a new wire.
  double section_factor = 1.0;
  // Drag of the mean wind per unstressed length [N/m] (a dead load like the
  // weight; set by simulation::static_configuration from conditions.wind).
  Eigen::Vector3d wind_load = Eigen::Vector3d::Zero();
};

enum class BarKind { dropper, steady_arm, stitch, other };
// How a bar goes slack (thesis 3.1.2):
//  none:   N = k (l - L0) always;
//  length: stiff only when longer than at static equilibrium:
//          N = N_eq + k max(l - l_eq, 0);
//  force:  no compression: N = max(k (l - L0), 0).
enum class SlackCriterion { none, length, force };

// Bar element (axial only, thesis 3.1.2).
struct BarElement {
  std::array<int, 2> nodes{};
  BarKind kind = BarKind::other;
  double stiffness = 0;          // axial stiffness k = EA/L [N/m]
  double mass = 0;               // total mass, lumped half to each node [kg]
  double unstressed_length = 0;  // L0 [m]; for droppers found by form-finding
  // EA [N] of a bar given by it ('droppers.EA'); 0: 'stiffness' is given as
  // is. When > 0, stiffness = EA / unstressed_length, kept so whenever L0
  // changes (set_bar_unstressed_length; form-finding).
  double axial_rigidity = 0;
  SlackCriterion slack = SlackCriterion::none;
  bool form_find_length = false;  // L0 is a form-finding unknown
  int span = -1;                  // span index (droppers), 0-based
  int index_in_span = -1;         // dropper number within its span, 0-based
  // Wind (docs/conditions.md): outer diameter [m] and drag coefficient [1];
  // 0: the default of the bar's kind (bar_diameter, bar_drag_coefficient).
  double diameter = 0;
  double drag_coefficient = 0;
  double equilibrium_length = 0;  // l_eq, set after the static solution
  double equilibrium_force = 0;   // N_eq, set after the static solution
};

// Sets a bar's unstressed length L0 and, for a bar given by its EA, its
// stiffness k = EA / L0.
inline void set_bar_unstressed_length(BarElement& bar, double L0) {
  bar.unstressed_length = L0;
  if (bar.axial_rigidity > 0) bar.stiffness = bar.axial_rigidity / L0;
}

// Default diameters [m] of bars for the wind's drag: a dropper of stranded
// bronze Bz 10 (7 x 1.35 mm: 4 mm), a stitch bar as a Bz 35 stitch wire
// (7.5 mm); steady arms and other bars none (a steady arm lies across the
// track, along a cross-wind: give a diameter in the design to load it).
// Drag coefficient 1.2 (stranded wire) for every kind (docs/conditions.md).
inline double default_bar_diameter(BarKind kind) {
  return kind == BarKind::dropper ? 0.004 : kind == BarKind::stitch ? 0.0075 : 0.0;
}
inline double bar_diameter(const BarElement& b) {
  return b.diameter > 0 ? b.diameter : default_bar_diameter(b.kind);
}
inline double bar_drag_coefficient(const BarElement& b) {
  return b.drag_coefficient > 0 ? b.drag_coefficient : 1.2;
}

struct PointMass {
  int node = -1;
  double mass = 0;  // [kg]
  std::string label;
};

// Linear spring from a node to its design position: along the coordinate
// 'dof' (0..2 = x, y, z), or, when 'direction' is not zero, along that unit
// vector (force k ((r - r_design) . d) d; a horizontal registration on curved
// track).
struct SupportSpring {
  int node = -1;
  int dof = 0;
  double stiffness = 0;  // [N/m]
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
};

// A constant force on a node (part of the loads, like gravity): the pull of
// a tensioning device, the part of a steady arm's weight not in a point mass.
struct NodeForce {
  int node = -1;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // [N]
  std::string label;
};

// A linear viscous damper from a node to the ground along coordinate 'dof'
// (0..2 = x, y, z): force -coefficient x velocity. The matched ends of a
// moving window (catenary/window.hpp) use it.
struct NodeDashpot {
  int node = -1;
  int dof = 2;
  double coefficient = 0;  // [N s/m]
};

// A penalty spring holding a node's coordinate 'dof' at its static value
// while 'active' (a moving window's end that is the line's anchored end;
// catenary/window.hpp): force stiffness x (u - u_static).
struct NodePin {
  int node = -1;
  int dof = 2;
  double stiffness = 0;  // [N/m]
  bool active = false;
};

// A tensioning device at a wire's end (parametric lines). Form-finding holds
// the end (x, y, z fixed); catenary::release_tensioning_devices() then frees
// it horizontally along 'direction' and applies the anchor's reaction as a
// NodeForce, so the static configuration stays an equilibrium:
//  weight: constant pull; effective mass 'mass' on the end (a point mass);
//  spring: pull = reaction + stiffness x (displacement along the pull).
enum class TensioningKind { weight, spring };
struct TensioningDevice {
  int node = -1;
  int wire = -1;
  TensioningKind kind = TensioningKind::weight;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // horizontal, away from the wire
  double mass = 0;                                       // [kg] weight: referred to the wire end
  double stiffness = 0;                                  // [N/m] spring
  bool released = false;
  double pull = 0;    // [N] along 'direction' in the static configuration (set on release)
  double travel = 0;  // [m] the wire end's travel each way from its design position (0: not given)
};

// A registration (steady arm) of a contact wire at a support: the node it
// holds and the horizontal unit normal of the track there (pull-off forces
// are reported along it).
struct Registration {
  int node = -1;
  int support = -1;  // index into support_x
  Eigen::Vector3d lateral = Eigen::Vector3d::UnitY();
};

// A stretch of the line for the statistics of a run (stations along the
// track): a tension section's own part, or an overlap.
struct LineZone {
  std::string name;  // "section 1", "overlap 1-2"
  bool overlap = false;
  double from_x = 0, to_x = 0;
};

// Contact-gap offset of a contact wire (irregularities between the droppers):
// the contact sees the wire at z + offset(x), offset interpolated linearly in
// the station table (x ascending), zero outside.
struct ContactGapOffset {
  std::vector<double> x, offset;
  // The offset at station x (linear in the table, zero outside) and its
  // slope d(offset)/dx (the slope of the piece holding x).
  double at(double station) const {
    const std::size_t i = piece(station);
    if (i == kNone) return 0.0;
    const double w = (station - x[i]) / (x[i + 1] - x[i]);
    return (1 - w) * offset[i] + w * offset[i + 1];
  }
  double slope_at(double station) const {
    const std::size_t i = piece(station);
    return i == kNone ? 0.0 : (offset[i + 1] - offset[i]) / (x[i + 1] - x[i]);
  }

 private:
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::size_t piece(double station) const {
    if (x.size() < 2 || station <= x.front() || station >= x.back()) return kNone;
    return static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), station) - x.begin()) - 1;
  }
};

// Form-finding: node 'node' must sit at height z in the static configuration.
struct HeightTarget {
  int node = -1;
  double z = 0;
  int bar = -1;  // the dropper whose unstressed length is the matching unknown
};

// Form-finding: the mean axial force of these cable elements (or, for a
// stitch wire built of bars, of these bars) must equal 'tension'; their
// unstressed lengths share one scale factor on their design lengths (the
// unknown).
struct TensionSegment {
  int wire = -1;              // -1 for a segment of bars
  std::vector<int> elements;  // cable elements
  std::vector<int> bars;      // or bars (then 'elements' is empty)
  double tension = 0;
};

// Ice on the wires (scene 'conditions.ice', docs/conditions.md): mass per
// length added to every wire of a kind after form-finding, so the line
// built for bare wires carries it (mass and weight) [kg/m].
struct IceLoad {
  double contact = 0, messenger = 0, stitch = 0;
  bool any() const { return contact > 0 || messenger > 0 || stitch > 0; }
  double on(WireKind kind) const {
    return kind == WireKind::contact     ? contact
           : kind == WireKind::messenger ? messenger
           : kind == WireKind::stitch    ? stitch
                                         : 0.0;
  }
};

// Mean wind on the wires (scene 'conditions.wind', docs/conditions.md):
// horizontal, 'speed' at the wires' height, blowing at 'direction_deg' to
// the x axis (the track on straight track): 90 = across the track towards
// +y. Drag per length of a wire, from the wind's component normal to it,
// q = rho Cd d |V_n| V_n / 2 (after form-finding, like ice). The blow-off
// check of the contact wire (pcsim static) compares its lateral position
// with the permissible one: working_half_width - vehicle_sway - track_tolerance.
// Turbulence of the wind (scene 'conditions.wind.turbulence'): u' along the
// mean wind and w' vertical, a seeded random field along x and time
// (catenary/wind_field.hpp) whose drag, linearised about the mean wind, is a
// time-dependent load in dynamic runs (assembly/wind_terms.hpp).
struct TurbulenceSettings {
  bool on = false;
  double intensity = 0;                // I_u = sigma_u / V [1]
  double length_scale = 0;             // L_u [m]
  double vertical_ratio = 0.5;         // sigma_w / sigma_u [1]
  double vertical_length_ratio = 0.1;  // L_w / L_u [1]
  double coherence_decay = 10;         // C of exp(-C f dx / V) [1]
  unsigned long seed = 1;
  double grid_spacing = 5;  // [m] stations of the field
  double time_step = 0.05;  // [s] times of the field
  int time_points = 2048;   // period time_points x time_step
};

struct WindLoad {
  TurbulenceSettings turbulence;
  double speed = 0;                  // [m/s]
  double direction_deg = 90;         // [deg]
  double air_density = 1.25;         // [kg/m^3]
  double working_half_width = 0.40;  // [m] (TSI ENE, 1600 mm head)
  double vehicle_sway = 0;           // [m]
  double track_tolerance = 0;        // [m]
  bool any() const { return speed > 0; }
  double permissible_m() const { return working_half_width - vehicle_sway - track_tolerance; }
  Eigen::Vector3d velocity() const {
    const double a = direction_deg * M_PI / 180;
    return {speed * std::cos(a), speed * std::sin(a), 0.0};
  }
};

// The conditions the line is under (scene 'conditions', docs/conditions.md):
// ice, the temperature's difference from the design temperature (the
// wires' unstressed lengths grow by alpha dT), the mean wind.
struct LineConditions {
  IceLoad ice;
  double temperature_change_k = 0;  // [K]
  WindLoad wind;
  bool any() const { return ice.any() || temperature_change_k != 0 || wind.any(); }
};

struct CatenaryMesh {
  std::string name;
  std::string source_file;
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
  std::vector<Node> nodes;
  std::vector<Wire> wires;
  std::vector<CableElement> cables;
  std::vector<BarElement> bars;
  std::vector<PointMass> point_masses;
  std::vector<SupportSpring> springs;
  std::vector<NodeForce> node_forces;
  std::vector<NodeDashpot> dashpots;
  std::vector<NodePin> pins;
  std::vector<TensioningDevice> tensioning_devices;
  std::vector<HeightTarget> height_targets;
  std::vector<TensionSegment> tension_segments;
  bool form_finding_default = false;  // true for parametric designs
  // Every span alike between the line's end anchors (a parametric design
  // that spans_differ, geometry.hpp, finds nothing in): what two spans show
  // holds for the others.
  bool identical_spans = false;
  // Track description (parametric designs; empty otherwise). 'x' of the
  // track is the station along the track centre (= x on straight track).
  TrackAlignment track;            // straight along x unless curved
  std::vector<double> support_x;   // station of every support [m]
  std::vector<int> support_nodes;  // contact-wire node in service at every support (uplift)
  std::vector<Registration> registrations;
  std::vector<LineZone> zones;
  // Contact wires: every wire of kind contact, in the order of their first
  // station (several along a line with overlaps); contact_wire is the first
  // (-1: none). contact_gap_offsets: empty, or one per contact wire.
  std::vector<int> contact_wires;
  int contact_wire = -1;
  std::vector<ContactGapOffset> contact_gap_offsets;
  double rayleigh_alpha = 0;  // C = alpha M + beta K (thesis 3.1)
  double rayleigh_beta = 0;
  LineConditions conditions;  // applied by simulation::static_configuration after form-finding

  // The contact wires (contact_wires, or contact_wire alone for a mesh that
  // only sets that).
  std::vector<int> contact_wire_list() const {
    if (!contact_wires.empty() || contact_wire < 0) return contact_wires;
    return {contact_wire};
  }

  int find_wire(const std::string& wire_name) const {
    for (std::size_t i = 0; i < wires.size(); ++i)
      if (wires[i].name == wire_name) return static_cast<int>(i);
    return -1;
  }
};

}  // namespace pcsim::catenary
