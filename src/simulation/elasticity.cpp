#include "pcsim/simulation/elasticity.hpp"

#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/contact/wire_locator.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/simulation/statics.hpp"

namespace pcsim::simulation {

namespace {

// Height of cable element e at chi for node values v.
double height_at(const catenary::CatenaryMesh& mesh, const std::vector<double>& v, int e,
                 double chi) {
  catenary::Vec12 q;
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 6; ++c) q[6 * a + c] = v[6 * mesh.cables[e].nodes[a] + c];
  return catenary::cable_point(mesh.cables[e].ref_length, q, chi).r.z();
}

}  // namespace

catenary::ElasticityResult static_elasticity(MPI_Comm comm,
                                             const simulation::StaticConfiguration& statics,
                                             const std::vector<double>& xs, double force) {
  const auto& mesh = statics.mesh;
  const auto& values = statics.result.node_values;
  std::vector<contact::ContactWireLocator> locators;
  for (int w : mesh.contact_wire_list()) locators.emplace_back(mesh, values, w);
  catenary::ElasticityResult result;
  result.force = force;
  for (double x : xs) {
    int element = -1, wire = -1;
    double chi = 0, z0 = 0;
    for (std::size_t w = 0; w < locators.size(); ++w) {  // the lowest wire at x
      int e;
      double c;
      if (!locators[w].locate(x, e, c)) continue;
      const double z = height_at(mesh, values, e, c);
      if (wire < 0 || z < z0) element = e, chi = c, z0 = z, wire = static_cast<int>(w);
    }
    if (wire < 0)
      throw InputError(mesh.source_file, "elasticity",
                       "x = " + std::to_string(x) + " m lies on no contact wire");
    assembly::CatenarySystem loaded(comm, mesh, 0, &statics.node_owner);
    loaded.point_loads().push_back({element, chi, Eigen::Vector3d(0, 0, force)});
    Vec state = loaded.create_vector();
    assembly::set_state_from_node_values(loaded, values, state);
    // Newton's round-off floor here is ~1e-5 N; 1e-4 N moves the wire by
    // 1e-4 N / (2500 N/m) = 4e-8 m. The configuration's own checks (inertia,
    // compression) were made on the static configuration: not repeated per point.
    const auto r = solvers::solve_static(loaded, state, false, "elasticity_", 1e-4, false);
    PCSIM_PETSC(VecDestroy(&state));
    result.x.push_back(x);
    result.uplift.push_back(height_at(mesh, r.node_values, element, chi) - z0);
    result.wire.push_back(wire);
  }
  return result;
}

}  // namespace pcsim::simulation
