// Locates a point x along the contact wire on a fixed (static) geometry: the
// contact-wire element and its local coordinate chi with x(chi) = x (thesis
// eq. 3.12). The contact point moves with the train, so the search starts
// from the element found last.
#pragma once

#include <array>
#include <vector>

#include "pcsim/catenary/mesh.hpp"

namespace pcsim::contact {

class ContactWireLocator {
 public:
  // node_values: 6 per node (the static configuration).
  ContactWireLocator(const catenary::CatenaryMesh& mesh, const std::vector<double>& node_values);
  // Element index (into mesh.cables) and local chi of the point at x; false if outside.
  bool locate(double x, int& element, double& chi) const;
  double x_min() const { return x_begin_; }
  double x_max() const { return x_end_; }

 private:
  const catenary::CatenaryMesh& mesh_;
  std::vector<int> elements_;              // contact-wire elements in order
  std::vector<double> node_x_;             // x of their first nodes, then the last node
  std::vector<std::array<double, 12>> q_;  // static element DOFs
  double x_begin_ = 0, x_end_ = 0;
  mutable int last_ = 0;
};

}  // namespace pcsim::contact
