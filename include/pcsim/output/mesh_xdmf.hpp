// Writes a CatenaryMesh (at given node positions) to HDF5 + XDMF for
// ParaView: the wires (cable elements) and the bars (droppers, stitch wires,
// ...) are separate grids of 2-node Polyline cells; the point masses are a
// Polyvertex grid. Every grid carries the same node attributes (displacement,
// node_wire, fixed_mask, point_mass, the extra fields), so that ParaView can
// colour every block by any of them. The XDMF refers to the .h5 by its file name only, so the
// two files must stay in the same folder (which can then be moved).
//
// HDF5 layout (n nodes, e cable elements, b bars; ints are 64-bit):
//   /nodes/position (n x 3)           positions passed in
//   /nodes/design_position (n x 3)    Node::position
//   /nodes/displacement (n x 3)       position - design_position
//   /nodes/wire (n)                   wire of the node, -1 if on no wire
//   /nodes/fixed (n x 6)              1 where a DOF is held
//   /nodes/fixed_mask (n)             x:1 + y:2 + z:4 (positions held)
//   /nodes/point_mass (n)             sum of the point masses at the node [kg]
//   /cables/connectivity (e x 2), /cables/wire, /cables/wire_kind,
//   /cables/ref_length, /cables/unstressed_length, /cables/tension_segment
//   /bars/connectivity (b x 2), /bars/kind, /bars/span, /bars/index_in_span,
//   /bars/stiffness, /bars/mass, /bars/unstressed_length
//   /point_masses/node, /point_masses/mass, /point_masses/label
//   /wires/name, /wires/kind
//   /fields/<name> (n x components)   extra node fields
// Kinds are the enum values of mesh.hpp: WireKind messenger 0, contact 1,
// stitch 2, other 3; BarKind dropper 0, steady_arm 1, stitch 2, other 3.
// The root group carries string attributes 'name' and 'source_file'.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"

namespace pcsim::output {

// An extra per-node quantity to show in ParaView (e.g. velocity, force).
struct NodeField {
  std::string name;            // dataset /fields/<name>; letters, digits, '_' only
  int components = 1;          // 1 (scalar) or 3 (vector)
  std::vector<double> values;  // components per node, node-major
  std::string unit = "1";      // its unit (dataset attribute 'unit')
};

// node_positions: 3 per node (x, y, z), e.g. the static solution, or the
// design positions. Every dataset carries its 'unit' and 'description'; the
// root group the provenance (output/provenance.hpp), if given. Throws
// std::invalid_argument on size mismatches and pcsim::SolverError if a file
// cannot be written.
void write_mesh_h5_xdmf(const catenary::CatenaryMesh& mesh,
                        const std::vector<double>& node_positions, const std::string& h5_path,
                        const std::string& xdmf_path,
                        const std::vector<NodeField>& node_fields = {},
                        const nlohmann::json& provenance = nlohmann::json());

// XDMF for mode shapes: a Temporal collection (time = mode number 0, 1, ...)
// whose every step holds the wires and bars grids of the mesh file written by
// write_mesh_h5_xdmf (mesh_h5_name: topology and /nodes/position) with a node
// vector attribute 'mode_shape' = modes_h5_name:/shapes/mode_<m> (n x 3), and
// as Grid attributes (VTK field data, which ParaView shows) the scalar
// 'frequency_hz' and, if 'vertical' has an entry for the mode, the integer
// 'vertical' (1: vertical mode, 0: lateral; modes_vertical(),
// catenary_results.hpp); also an Information 'frequency_hz'. Both names are
// bare file names in the folder of xdmf_path; modes whose shape dataset is
// absent from the modes file are left out. Throws std::invalid_argument for a
// name with a '/', and pcsim::SolverError if the files cannot be read or written.
void write_modes_xdmf(const catenary::CatenaryMesh& mesh, const std::string& modes_h5_name,
                      const std::string& mesh_h5_name, const std::vector<double>& frequencies_hz,
                      const std::string& xdmf_path, const std::vector<long>& vertical = {});

// XDMF for a time series of field snapshots: a Temporal collection (time in s)
// of the wires and bars grids of mesh_h5_name (the static configuration) with
// a node vector attribute 'displacement' =
// snapshots_h5_name:/snapshots/xdmf/displacement_<k> (n x 3), the displacement
// from that configuration (ParaView: Warp By Vector animates the wires), and,
// with pantographs > 0, a grid 'pantographs': for each pantograph a line from
// its head to its contact point (points /snapshots/xdmf/pantograph_points_<k>,
// cells /snapshots/xdmf/pantograph_cells), the node vector 'displacement'
// (zero: /snapshots/xdmf/pantograph_displacement) and the cell scalar
// 'contact_force' (/snapshots/xdmf/contact_force_<k>). In a run's results.h5
// the per-snapshot datasets are HDF5 virtual datasets, views of row k of
// /snapshots/<name> (VTK's XDMF3 reader reads no HyperSlab items).
void write_snapshots_xdmf(const catenary::CatenaryMesh& mesh, const std::string& mesh_h5_name,
                          const std::string& snapshots_h5_name, const std::vector<double>& times,
                          const std::string& xdmf_path, std::size_t pantographs = 0);

// Design positions of every node, 3 per node (for write_mesh_h5_xdmf).
std::vector<double> design_positions(const catenary::CatenaryMesh& mesh);

}  // namespace pcsim::output
