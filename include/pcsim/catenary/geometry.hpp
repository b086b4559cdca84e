// Catenary geometry: plain design parameters -> CatenaryMesh (mesh.hpp).
//
// Two kinds of design (docs/design-format.md lists every key of the design
// files that fill these structs):
//  - ParametricDesign: a line of simple (or stitched) catenary: one or
//    several tension sections joined by overlaps, tensioning devices, presag
//    profiles, dropper positions per span, support and steady-arm models,
//    contact-wire irregularities and wear, curved track;
//  - ExplicitDesign: arbitrary nodes, cable wires, bars, supports, masses,
//    springs and form-finding targets, for small verification structures.
//
// The builders check every value that can be wrong whoever fills the struct
// (ranges, geometry, references); a problem throws pcsim::InputError naming
// design.file, the key path of the offending value in the design-file format
// (e.g. 'droppers.positions[3]', 'bars[0].nodes[1]') and the reason.
// Reading a design file (syntax, unknown keys) is pcsim/scene/design_reader.hpp.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::catenary {

// Rayleigh damping C = alpha M + beta K (thesis 3.1); both >= 0.
struct RayleighDamping {
  double alpha = 0;  // [1/s]
  double beta = 0;   // [s]
};

// ------------------------------------------------------------ parametric ----

// Cable properties of one wire ('wires.contact', 'wires.messenger').
struct CableDesign {
  double mass_per_length = 0;                          // [kg/m] > 0
  double EA = 0;                                       // [N] > 0
  double EI = 0;                                       // [N m^2] >= 0
  double tension = 0;                                  // design tension [N] > 0
  double thermal_expansion = kCopperThermalExpansion;  // [1/K] >= 0 (last: aggregate order)
  double diameter = 0;                                 // [m] for wind; 0: the wire kind's default
  double drag_coefficient = 0;                         // [1] for wind; 0: the wire kind's default
};

// Contact-wire presag in a span whose two supports hold the wire in service.
enum class PresagProfile {
  parabola,  // between the supports, sag 'presag' at mid-span
  droppers,  // through the first and last droppers (at support height), sag 'presag' midway
  heights,   // explicit: the sag at each dropper ('droppers.sags'), linear in between
};

// Dropper positions (and sags, presag profile 'heights') of given spans.
struct SpanDroppers {
  std::vector<long> spans;        // 1-based span numbers
  std::vector<double> positions;  // [m] from the span's first support
  std::vector<double> sags;       // [m] contact-wire sag at each dropper (profile 'heights')
};

struct DropperDesign {
  std::vector<double> positions;    // [m] from each span's first support, strictly in (0, L)
  std::vector<double> sags;         // [m] presag profile 'heights': sag at each dropper
  std::vector<SpanDroppers> spans;  // spans with their own positions
  // Axial stiffness: exactly one of 'stiffness' (k [N/m], every dropper),
  // 'EA' (one EA [N] for every dropper) and 'EA_per_position' (one EA [N] per
  // position, index as in 'positions' and in every 'spans' entry). With EA,
  // each dropper's k = EA / L0, L0 its unstressed length (form-found).
  double stiffness = 0;                 // [N/m] > 0; 0: EA given
  std::optional<double> EA;             // [N] > 0; empty: not given
  std::vector<double> EA_per_position;  // [N] > 0; empty: not given
  double mass_per_length = 0;           // [kg/m] >= 0
  SlackCriterion slack = SlackCriterion::length;
  double clamp_mass_messenger = 0;            // [kg] >= 0
  double clamp_mass_contact = 0;              // [kg] >= 0
  double diameter = 0, drag_coefficient = 0;  // wind; 0: a dropper's default
};

// Stitch wire at every support inside a tension section ('stitch_wire').
struct StitchWireDesign {
  double length = 0;   // total length [m], 0 < length < span length
  double tension = 0;  // form-found like the main wires [N]
  double mass_per_length = 0;
  double EA = 0;
};

// One tension section: the spans of the line it owns, and its track.
struct SectionDesign {
  long spans = 0;     // >= 1; the sections' spans add up to spans.count
  double radius = 0;  // horizontal radius of the track [m]; 0 straight, > 0 left, < 0 right
};

// Overlap between two consecutive tension sections (docs/design-format.md).
struct OverlapDesign {
  long spans = 2;             // m >= 1 spans between the supports where one wire is raised
  double raise = 0.3;         // out-of-service wire above the in-service one there [m]
  double anchor_raise = 0.6;  // wire ends at the anchors above the contact height [m]
  double separation = 0.2;    // lateral distance between the two wires [m]
};

enum class TensioningDeviceKind { fixed, weight, spring };
// Tensioning device at every end of every section (both wires).
struct TensioningDesign {
  TensioningDeviceKind device = TensioningDeviceKind::fixed;
  double ratio = 1;                   // weight: wire tension / weight force, >= 1
  std::optional<double> weight_mass;  // weight [kg]; default: tension / (g ratio)
  double stiffness = 0;               // spring [N/m] > 0
  double travel = 0;                  // the wire end's travel each way [m] (0: not given)
};

enum class MessengerSupportModel { fixed, spring, spring_mass };
struct MessengerSupportDesign {
  MessengerSupportModel model = MessengerSupportModel::fixed;
  double stiffness = 0;  // vertical [N/m] (spring, spring_mass)
  double mass = 0;       // [kg] (spring_mass)
};

enum class SteadyArmModel { constraint, hinged, spring };
struct SteadyArmDesign {
  SteadyArmModel model = SteadyArmModel::constraint;
  double mass = 0;                 // [kg] >= 0
  double length = 1.0;             // hinged: pivot to wire [m]
  double axial_stiffness = 1.0e7;  // hinged: the arm as a bar [N/m]
  double stiffness = 0;            // spring: vertical [N/m]
};

// Support models of given supports (0-based support numbers).
struct SupportOverride {
  std::vector<long> supports;
  std::optional<MessengerSupportDesign> messenger;
  std::optional<SteadyArmDesign> steady_arm;
};

enum class IrregularitySpectrum { uniform, power_law };
// Random contact-wire height profile: a sum of cosines over the wavelength
// band with random phases (seeded), scaled to the RMS amplitude.
struct RandomIrregularity {
  double rms = 0;               // [m] >= 0
  double wavelength_min = 1.0;  // [m] > 0
  double wavelength_max = 50.0;
  IrregularitySpectrum spectrum = IrregularitySpectrum::uniform;
  double exponent = 2.0;  // power_law: PSD ~ wavenumber^-exponent
  long seed = 1;
};

// Reduced section (wear) over a stretch of the contact wires.
struct WearStretch {
  double from = 0, to = 0;  // stations [m]
  double section_loss = 0;  // fraction of the section worn away, in [0, 1)
};

struct IrregularityDesign {
  std::string profile_key = "irregularities.profile";  // where the table came from (messages)
  std::vector<double> profile_x, profile_dz;           // prescribed (x, dz) [m], x increasing
  std::optional<RandomIrregularity> random;
  std::vector<WearStretch> wear;
  bool empty() const { return profile_x.empty() && !random && wear.empty(); }
};

struct ParametricDesign {
  std::string file;  // design file, named in errors; mesh.source_file
  std::string name;  // mesh.name
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
  RayleighDamping damping;
  long span_count = 0;     // 'spans.count', 1..100000
  double span_length = 0;  // 'spans.length' [m]
  double system_height = 0;
  double contact_wire_height = 0;
  double presag = 0;
  std::string presag_key = "presag";  // where the sag came from ('presag.sag' in the map; messages)
  PresagProfile presag_profile = PresagProfile::parabola;
  double stagger = 0;
  double messenger_stagger = 0;
  double element_length = 0.5;  // target element length along x [m]
  CableDesign contact, messenger;
  DropperDesign droppers;
  SteadyArmDesign steady_arms;
  MessengerSupportDesign messenger_supports;
  std::vector<SupportOverride> support_overrides;
  std::optional<StitchWireDesign> stitch_wire;
  std::vector<SectionDesign> sections;  // empty: one straight section over every span
  OverlapDesign overlap;
  TensioningDesign tensioning;
  IrregularityDesign irregularities;
};

// -------------------------------------------------------------- explicit ----

// A node: an index into the design's nodes (listed, then created by wires in
// order), or, when 'wire' is given, the 'node'-th node along a wire
// defined earlier (negative counts from the wire's end).
struct NodeRef {
  long index = -1;
  std::optional<std::string> wire;
  long node = 0;

  static NodeRef at(long node_index) { return {node_index, std::nullopt, 0}; }
  static NodeRef on_wire(std::string wire_name, long k) { return {-1, std::move(wire_name), k}; }
};

// Straight wire from 'from' to 'to' cut into 'elements' equal elements.
struct WireRun {
  NodeRef from, to;
  long elements = 0;
};

struct ExplicitWire {
  std::string name;
  WireKind kind = WireKind::other;
  double mass_per_length = 0;  // > 0
  double EA = 0;               // > 0
  double EI = 0;               // >= 0
  double tension = 0;          // >= 0
  std::vector<NodeRef> nodes;  // the wire's nodes, used when 'run' is empty
  std::optional<WireRun> run;
  std::optional<double> unstressed_ratio;              // L0/Lref > 0; empty: taut at 'tension'
  double thermal_expansion = kCopperThermalExpansion;  // [1/K] >= 0
  double diameter = 0;                                 // [m] for wind; 0: the wire kind's default
  double drag_coefficient = 0;                         // [1] for wind; 0: the wire kind's default
};

struct ExplicitBar {
  std::array<NodeRef, 2> nodes;
  BarKind kind = BarKind::other;
  double stiffness = 0;                     // > 0
  double mass = 0;                          // >= 0
  std::optional<double> unstressed_length;  // > 0; empty: design length
  SlackCriterion slack = SlackCriterion::none;
  bool form_find = false;
  long span = -1;  // -1: none
  long index_in_span = -1;
  double diameter = 0, drag_coefficient = 0;  // wind; 0: the kind's default
};

struct ExplicitSupport {
  NodeRef node;
  std::vector<int> dofs = {0, 1, 2};  // held DOFs: 0..2 position, 3..5 slope
};

struct ExplicitPointMass {
  NodeRef node;
  double mass = 0;  // > 0
  std::string label = "point_mass";
};

struct ExplicitSpring {
  NodeRef node;
  int dof = 0;  // 0..2 (x, y, z)
  double stiffness = 0;
};

struct ExplicitTarget {
  NodeRef node;
  std::optional<double> z;  // empty: the node's design height
  long bar = -1;            // a form-finding bar
};

struct ExplicitTensionSegment {
  std::string wire;
  std::optional<double> tension;  // empty: the wire's tension
};

struct ExplicitDesign {
  std::string file;
  std::string name;
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
  RayleighDamping damping;
  bool form_finding = false;
  std::vector<Eigen::Vector3d> nodes;
  std::vector<ExplicitWire> wires;
  std::vector<ExplicitBar> bars;
  std::vector<ExplicitSupport> supports;
  std::vector<ExplicitPointMass> point_masses;
  std::vector<ExplicitSpring> springs;
  std::vector<ExplicitTarget> targets;
  std::vector<ExplicitTensionSegment> tension_segments;
  std::vector<NodeRef> support_nodes;
};

// ------------------------------------------------------------- builders ----

// Both throw pcsim::InputError(design.file, key, reason) on a bad value, and
// on a mesh that fails mesh_consistency_error.
CatenaryMesh build_parametric(const ParametricDesign& design);
CatenaryMesh build_explicit(const ExplicitDesign& design);
// Why the spans of 'design' are not all alike, "" if they are (one straight
// section, no support overrides, no irregularities, the same droppers in
// every span; a stitch wire is in every span): CatenaryMesh::identical_spans.
std::string spans_differ(const ParametricDesign& design);

// ---------------------------------------------------------------- sizes ----

// Size of the mesh a design builds, counted without building it (the memory
// estimate refuses a design too large for the machine before allocating).
struct MeshSize {
  long nodes = 0;                  // every node
  long cable_nodes = 0;            // nodes of cable elements (6 DOFs each; the others 3)
  long cables = 0;                 // ANCF cable elements
  long bars = 0;                   // droppers, stitch wires, other bars
  long fixed_dofs = 0;             // DOFs held by supports
  long form_finding_unknowns = 0;  // height targets + tension segments
  std::string file;                // the design file
  std::string key;                 // the key that sets the size ('spans.count', ...)
  // Unknowns of the catenary system (fixed DOFs and slopes of bar-only nodes excluded).
  long dofs() const { return 6 * cable_nodes + 3 * (nodes - cable_nodes) - fixed_dofs; }
};
// Both run the design's range checks first (the builders' InputErrors).
MeshSize mesh_size(const ParametricDesign& design);
MeshSize mesh_size(const ExplicitDesign& design);
// Of a built mesh (tests compare the counts with it).
MeshSize mesh_size(const CatenaryMesh& mesh);

// Internal consistency of a mesh (indices in range, element lengths positive,
// targets pointing at form-finding bars, ...). Returns an empty string when
// the mesh is consistent, otherwise a description of the first problem.
// Used by the builders, the tests, and code that builds meshes by hand.
std::string mesh_consistency_error(const CatenaryMesh& mesh);

}  // namespace pcsim::catenary
