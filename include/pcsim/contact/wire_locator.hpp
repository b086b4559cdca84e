// Locates a point along one contact wire on a fixed (static) geometry: the
// wire's element and its local coordinate chi where the wire crosses the
// vertical plane normal to the track at station x (thesis eq. 3.12: on
// straight track the station is x, and x(chi) = x is the cubic of the
// thesis). The contact point moves with the train, so the search starts from
// the element found last.
#pragma once

#include <array>
#include <vector>

#include "pcsim/catenary/mesh.hpp"

namespace pcsim::contact {

class ContactWireLocator {
 public:
  // node_values: 6 per node (the static configuration); wire: index into
  // mesh.wires of a contact wire (its nodes must advance in station).
  ContactWireLocator(const catenary::CatenaryMesh& mesh, const std::vector<double>& node_values,
                     int wire);
  // Element index (into mesh.cables) and local chi of the point at station
  // x; false if x lies outside the wire.
  bool locate(double x, int& element, double& chi) const;
  int wire() const { return wire_; }
  double x_min() const { return x_begin_; }
  double x_max() const { return x_end_; }

 private:
  double curved_chi(int i, double x) const;
  const catenary::CatenaryMesh& mesh_;
  int wire_ = -1;
  std::vector<int> elements_;              // the wire's elements in order
  std::vector<double> node_x_;             // station of their first nodes, then the last node
  std::vector<std::array<double, 12>> q_;  // static element DOFs
  double x_begin_ = 0, x_end_ = 0;
  mutable int last_ = 0;
};

}  // namespace pcsim::contact
