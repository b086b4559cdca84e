// The parametric line builder (geometry_parametric.cpp and the files it
// uses): the layout of the tension sections over the supports, the design
// geometry of a section's wires, the contact-wire irregularities, and the
// builder of one section.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "geometry_internal.hpp"

namespace pcsim::catenary::detail {

// Key points (supports, dropper points, stitch clamps) closer than this are
// rejected: they would make a needlessly tiny, very stiff element.
constexpr double kMinKeyPointGap = 0.05;  // [m]
// Key points closer than this are the same point.
constexpr double kSamePoint = 1e-9;  // [m]

// What a section's wires do at a support of the line.
enum class Role {
  none,     // not there
  service,  // at contact height (the section's own supports, or both wires of an overlap)
  raised,   // out of service: 'overlap.raise' above the contact height
  anchor,   // the wire ends at an overlap's anchor, 'overlap.anchor_raise' above
};

struct SectionLayout {
  int first = 0, last = 0;          // supports where the section's wires start and end
  int own_first = 0, own_last = 0;  // the stretch of the line the section owns (sections[i].spans)
  std::vector<Role> role;           // per support of the line
  // Per support, in units of overlap.separation: the wire's shift across the
  // track from the stagger where several sections' wires meet (+-1/2 for
  // two, + for the earlier section; +1, 0, -1 for three), 0 elsewhere.
  std::vector<double> lateral_shift;
};

struct LineLayout {
  int spans = 0;
  double L = 0;
  std::vector<SectionLayout> sections;
  std::vector<int> overlap_first;  // first support q of each overlap (q .. q + m)
  int overlap_spans = 0;
  TrackAlignment track;
};

// Every range check of a parametric design (InputError naming the key;
// geometry_parametric.cpp).
void check_parametric(const ParametricDesign& in);

// Sections, overlaps and the track of a design; throws InputError on a line
// whose sections cannot hold their overlaps.
LineLayout make_line_layout(const ParametricDesign& in);

// The contact-wire height profile dz(station) of 'irregularities'
// (prescribed table + random cosines).
class IrregularProfile {
 public:
  explicit IrregularProfile(const IrregularityDesign& in, double line_length);
  bool empty() const { return empty_; }
  double dz(double x) const;
  // Sample spacing that resolves the profile (table or shortest wavelength).
  double resolution() const { return resolution_; }

 private:
  const IrregularityDesign& in_;
  std::vector<double> k_, a_, phase_;  // wavenumbers, amplitudes, phases of the random part
  double resolution_ = 0.1;
  bool empty_ = true;
};

// Design geometry of one section's wires: s is the distance from the first
// support of span j (a span of the line).
class SectionGeometry {
 public:
  SectionGeometry(const ParametricDesign& in, const LineLayout& line, int section,
                  const IrregularProfile& profile);
  const SectionLayout& layout() const { return line_.sections[section_]; }
  Role role(int k) const { return layout().role[k]; }
  bool dropper_span(int j) const;  // both supports on the wire, neither an anchor
  bool service_span(int j) const;  // both supports in service (presag applies)
  bool anchor_span(int j) const;   // one end is an anchor (no droppers)
  bool stitch_at(int k) const;     // a stitch wire at support k
  const std::vector<double>& positions(int j) const;  // dropper positions of span j
  const std::vector<double>& sags(int j) const;       // their sags (profile heights)
  std::string positions_key(int j) const;  // 'droppers.positions' or 'droppers.spans[i]...'

  double messenger_sag = 0;  // in the dropper spans [m]
  Eigen::Vector3d contact(int j, double s) const;
  Eigen::Vector3d contact_tangent(int j, double s) const;
  Eigen::Vector3d messenger(int j, double s, double sag) const;
  Eigen::Vector3d messenger(int j, double s) const { return messenger(j, s, messenger_sag); }
  Eigen::Vector3d messenger_tangent(int j, double s) const;
  double support_z(int k) const;                // contact wire at support k
  double lateral(int k, bool messenger) const;  // offset from the track centre at support k
  Eigen::Vector3d track_normal(int k) const;    // horizontal, left of the track at support k
  Eigen::Vector3d track_tangent(int k) const;

 private:
  Eigen::Vector3d plan_point(int j, double s, double y_left, double y_right, double z) const;
  Eigen::Vector2d plan_slope(int j, double y_left, double y_right) const;
  double presag(int j, double s, double* slope) const;
  const ParametricDesign& in_;
  const LineLayout& line_;
  int section_;
  const IrregularProfile& profile_;
  std::map<long, int> span_override_;  // 0-based span -> index into droppers.spans
  double contact_anchor_sag_ = 0, messenger_anchor_sag_ = 0;  // free sag in anchor spans
};

// Builds one tension section into the mesh (geometry_section.cpp,
// geometry_supports.cpp): its contact wire, messenger, stitch wires,
// droppers, supports, steady arms and tensioning devices.
class SectionBuilder {
 public:
  SectionBuilder(const ParametricDesign& in, const LineLayout& line, int section,
                 const IrregularProfile& profile, CatenaryMesh& mesh);
  void build();
  // Adds the size of the section's mesh to 'size', counted span by span
  // without building it (geometry_size.cpp; the same key points and supports).
  void add_size(MeshSize& size) const;
  int contact_wire() const { return contact_wire_; }
  // Contact-wire node at support k of the line (-1 if none).
  int contact_node_at(int k) const;
  // Stations of the contact wire's held points (height targets, wire ends).
  std::vector<double> held_stations() const;

 private:
  enum class KeyKind { support, dropper, stitch_clamp };
  struct KeyPoint {
    double s = 0;
    KeyKind kind = KeyKind::support;
    int index = -1;  // dropper index for droppers
  };
  struct Station {
    int span;
    double s;
    KeyKind kind;
    int dropper;  // dropper index at dropper stations, -2 at plain nodes
  };
  static bool is_plain(const Station& st) { return st.dropper == -2; }
  static bool is_support(const Station& st) { return !is_plain(st) && st.kind == KeyKind::support; }
  static bool is_dropper(const Station& st) { return !is_plain(st) && st.kind == KeyKind::dropper; }
  std::string describe(const KeyPoint& k) const;
  std::vector<KeyPoint> span_key_points(int j) const;
  void make_stations();
  int stitch_support_of(int j, double s) const;
  Eigen::Vector3d upper_point(int j, double s, double sag) const;
  double hung_mass(double sag) const;
  void find_messenger_sag();
  void place_nodes();
  void add_wire(const std::string& name, WireKind kind, const CableDesign& p, int first_node);
  void add_stitch_wires();
  void add_stitch_wire(int k);
  [[noreturn]] void fail_dropper_below_upper_wire(const Station& st, int i, bool on_stitch) const;
  void add_droppers();
  // geometry_supports.cpp
  void add_supports();
  void add_messenger_support(int k, int node);
  void add_steady_arm(int k, int node);
  void add_hinged_arm(int k, int node, const SteadyArmDesign& arm);
  void hold_laterally(int k, int node);
  void add_tensioning_device(int k, int node, int wire, double tension);
  const MessengerSupportDesign& messenger_support(int k) const;
  const SteadyArmDesign& steady_arm(int k) const;
  double steady_arm_weight_mass(int k) const;

  const ParametricDesign& in_;
  const LineLayout& line_;
  const int section_;
  const double L_;
  SectionGeometry geo_;
  CatenaryMesh& mesh_;
  std::vector<Station> stations_;
  int S_ = 0;     // stations = nodes per wire
  int base_ = 0;  // first node of the section (its contact wire's)
  int contact_wire_ = -1, messenger_wire_ = -1;
  std::vector<int> support_station_;           // station of each support first..last
  std::map<int, int> stitch_node_of_station_;  // contact station -> stitch node
};

// Irregularities after the sections are built: the contact-gap offsets
// (profile between the held points) and the worn stretches.
void add_contact_gap_offsets(CatenaryMesh& mesh, const IrregularProfile& profile,
                             const std::vector<std::vector<double>>& held_stations);
void apply_wear(CatenaryMesh& mesh, const IrregularityDesign& in);

}  // namespace pcsim::catenary::detail
