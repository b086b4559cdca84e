// Mesh sizes of designs, counted without building the mesh (geometry.hpp).
#include <algorithm>
#include <cmath>
#include <set>

#include "geometry_internal.hpp"

namespace pcsim::catenary {

namespace {

// Stations (nodes per wire) that span j contributes, its last support excluded.
long span_stations(const ParametricDesign& in, int j) {
  const auto keys = detail::span_key_points(in, j);
  long n = 0;
  for (std::size_t k = 0; k + 1 < keys.size(); ++k)
    n += std::max(
        1L, static_cast<long>(std::ceil((keys[k + 1].s - keys[k].s) / in.element_length - 1e-9)));
  return n;
}

}  // namespace

MeshSize mesh_size(const ParametricDesign& in) {
  detail::check_parametric(in);
  const long N = in.span_count;
  const long D = static_cast<long>(in.droppers.positions.size());
  // Spans differ only by the stitch clamps of their end supports: the first,
  // one inner and the last span give every kind.
  long stations = 1;  // the last support
  std::set<long> kinds = {0, std::min(1L, N - 1), N - 1};
  for (long j : kinds) {
    const long copies = (j == 1 && N > 2) ? N - 2 : 1;
    stations += copies * span_stations(in, static_cast<int>(j));
  }
  // Stitch wires: one bar chain per intermediate support through the dropper
  // points strictly inside its length.
  long stitch_nodes = 0, stitch_bars = 0;
  if (in.stitch_wire && N > 1) {
    const double half = 0.5 * in.stitch_wire->length, L = in.span_length;
    long inside = 0;
    for (double s : in.droppers.positions)
      if (s < half - detail::kSamePoint || s > L - half + detail::kSamePoint) ++inside;
    stitch_nodes = (N - 1) * inside;
    stitch_bars = (N - 1) * (inside + 1);
  }
  MeshSize size;
  size.file = in.file;
  size.key = "spans.count";
  size.cable_nodes = 2 * stations;
  size.nodes = size.cable_nodes + stitch_nodes;
  size.cables = 2 * (stations - 1);
  size.bars = N * D + stitch_bars;
  // Messenger pinned at every support, contact wire at both ends, steady arms hold y.
  size.fixed_dofs = 3 * (N + 1) + 6 + (N - 1);
  size.form_finding_unknowns = N * D + 2 * N;
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
