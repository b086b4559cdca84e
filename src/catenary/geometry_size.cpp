// Mesh sizes of designs, counted without building the mesh (geometry.hpp).
#include <algorithm>
#include <cmath>

#include "geometry_line.hpp"

namespace pcsim::catenary {

namespace detail {

namespace {

// Fixed DOFs of a registration's lateral hold (hold_laterally): the y DOF on
// straight track, a spring (none) where the track normal is not y.
long lateral_hold_dofs(const SectionGeometry& geo, int k) {
  return std::abs(geo.track_normal(k).x()) < 1e-12 ? 1 : 0;
}

}  // namespace

// The same stations, droppers, stitch wires and supports as build() (geometry_section.cpp,
// geometry_supports.cpp), counted.
void SectionBuilder::add_size(MeshSize& size) const {
  const auto& sec = geo_.layout();
  long stations = 1, droppers = 0;  // the last support's station
  for (int j = sec.first; j < sec.last; ++j) {
    const auto keys = span_key_points(j);
    for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
      const double a = keys[k].s, b = keys[k + 1].s;
      stations += element_count(b - a, in_.element_length);
      droppers += keys[k].kind == KeyKind::dropper ? 1 : 0;
    }
  }
  long stitch_nodes = 0, stitch_bars = 0, stitch_wires = 0;
  for (int k = sec.first + 1; k < sec.last && in_.stitch_wire; ++k) {
    if (!geo_.stitch_at(k)) continue;
    const double half = 0.5 * in_.stitch_wire->length;
    long inside = 0;  // dropper points strictly between the wire's two messenger clamps
    for (int j : {k - 1, k})
      for (const auto& key : span_key_points(j)) {
        const double x = j * L_ + key.s;
        inside += key.kind == KeyKind::dropper && x > k * L_ - half + kSamePoint &&
                  x < k * L_ + half - kSamePoint;
      }
    stitch_nodes += inside;
    stitch_bars += inside + 1;
    ++stitch_wires;
  }
  long fixed = 12, pivots = 0;  // both wires held in x, y, z at both ends
  for (int k = sec.first + 1; k < sec.last; ++k) {
    fixed += messenger_support(k).model == MessengerSupportModel::fixed ? 3 : 2;
    if (geo_.role(k) == Role::raised)
      fixed += lateral_hold_dofs(geo_, k) + 1;
    else if (steady_arm(k).model == SteadyArmModel::hinged)
      ++pivots;  // a fixed pivot node and its bar
    else
      fixed += lateral_hold_dofs(geo_, k);
  }
  if (in_.tensioning.device == TensioningDeviceKind::weight) ++fixed;  // midpoint anchor
  const long spans = sec.last - sec.first;
  const long segments = spans + (line_.sections.size() == 1 ? spans : 1) + stitch_wires;
  size.cable_nodes += 2 * stations;
  size.nodes += 2 * stations + stitch_nodes + pivots;
  size.cables += 2 * (stations - 1);
  size.bars += droppers + stitch_bars + pivots;
  size.fixed_dofs += fixed + 3 * pivots;
  size.form_finding_unknowns += droppers + segments;
}

}  // namespace detail

MeshSize mesh_size(const ParametricDesign& in) {
  detail::check_parametric(in);
  const detail::LineLayout line = detail::make_line_layout(in);
  // The counts do not depend on the heights: no irregular profile, no mesh.
  static const IrregularityDesign flat;
  const detail::IrregularProfile profile(flat, 0.0);
  CatenaryMesh unused;
  MeshSize size;
  size.file = in.file;
  // The key that makes the mesh large: the one of the larger factor, the
  // elements per span or the spans (a memory error names it).
  const bool fine = in.span_length / in.element_length > static_cast<double>(in.span_count);
  size.key = fine ? "element_length" : "spans.count";
  for (std::size_t i = 0; i < line.sections.size(); ++i)
    detail::SectionBuilder(in, line, static_cast<int>(i), profile, unused).add_size(size);
  return size;
}

MeshSize mesh_size(const ExplicitDesign& in) {
  MeshSize size;
  size.file = in.file;
  size.key = "nodes";
  size.nodes = static_cast<long>(in.nodes.size());
  long largest = 0;
  for (std::size_t i = 0; i < in.wires.size(); ++i) {
    const auto& w = in.wires[i];
    const long elements = w.run ? w.run->elements : static_cast<long>(w.nodes.size()) - 1;
    if (elements < 1) continue;  // the builder names the problem
    if (w.run) size.nodes += elements - 1;
    size.cable_nodes += elements + 1;
    size.cables += elements;
    if (w.run && elements > largest) {
      largest = elements;
      size.key = "wires[" + std::to_string(i) + "].nodes.elements";
    }
  }
  size.bars = static_cast<long>(in.bars.size());
  for (const auto& s : in.supports) size.fixed_dofs += static_cast<long>(s.dofs.size());
  size.form_finding_unknowns = static_cast<long>(in.targets.size() + in.tension_segments.size());
  return size;
}

MeshSize mesh_size(const CatenaryMesh& mesh) {
  MeshSize size;
  size.file = mesh.source_file;
  size.nodes = static_cast<long>(mesh.nodes.size());
  std::vector<bool> on_cable(mesh.nodes.size(), false);
  for (const auto& e : mesh.cables) on_cable[e.nodes[0]] = on_cable[e.nodes[1]] = true;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    size.cable_nodes += on_cable[n] ? 1 : 0;
    for (int c = 0; c < (on_cable[n] ? kNodeDofs : 3); ++c)
      size.fixed_dofs += mesh.nodes[n].fixed[c] ? 1 : 0;
  }
  size.cables = static_cast<long>(mesh.cables.size());
  size.bars = static_cast<long>(mesh.bars.size());
  size.form_finding_unknowns =
      static_cast<long>(mesh.height_targets.size() + mesh.tension_segments.size());
  return size;
}

}  // namespace pcsim::catenary
