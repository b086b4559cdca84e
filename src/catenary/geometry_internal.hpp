// Helpers shared by the catenary geometry builders (geometry_*.cpp).
#pragma once

#include <string>
#include <vector>

#include "pcsim/catenary/geometry.hpp"
#include "pcsim/core/limits.hpp"

namespace pcsim::catenary::detail {

// Number as written in messages ("61", "0.05", "-20000").

// Range checks of a design value: throw InputError(file, key, reason) with
// the reasons of the design-file reader ("must be positive (got -5)").
void require_positive(const std::string& file, const std::string& key, double value);
void require_nonnegative(const std::string& file, const std::string& key, double value);
// The same, and within the limit's bounds (pcsim/core/limits.hpp).
void require_positive(const std::string& file, const std::string& key, double value,
                      const Limit& limit);
void require_nonnegative(const std::string& file, const std::string& key, double value,
                         const Limit& limit);

// Gravity, damping and the file name common to both kinds of design.
void set_common(CatenaryMesh& mesh, const std::string& file, const std::string& name,
                const Eigen::Vector3d& gravity, const RayleighDamping& damping);

// Elements of length at most 'element_length' on a stretch of 'length'
// (at least 1), saturated at 1e12 instead of overflowing: the size check
// refuses such a mesh before anything is built.
long element_count(double length, double element_length);

// Unit vector of a, or zero for a zero vector.
Eigen::Vector3d unit(const Eigen::Vector3d& a);

// Gives every node of a wire the unit tangent of the polyline through its
// nodes (mean of the adjacent element directions at interior nodes).
void set_polyline_slopes(CatenaryMesh& mesh, const std::vector<int>& nodes);

// Stretch lambda = Lref/L0 at which a straight cable element of the
// elements.hpp law (T = EA eps lambda, eps = (lambda^2 - 1)/2) carries T.
double taut_stretch(double tension, double EA);

// Throws InputError(file, "", "inconsistent mesh: ...") if the mesh fails
// mesh_consistency_error.
void require_consistent(const CatenaryMesh& mesh, const std::string& file);

}  // namespace pcsim::catenary::detail
