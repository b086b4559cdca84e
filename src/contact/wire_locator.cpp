#include "pcsim/contact/wire_locator.hpp"

#include <algorithm>

#include "pcsim/contact/contact_kernel.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::contact {

using catenary::CatenaryMesh;

ContactWireLocator::ContactWireLocator(const CatenaryMesh& mesh,
                                       const std::vector<double>& node_values)
    : mesh_(mesh) {
  if (mesh.contact_wire < 0)
    throw InputError(mesh.source_file, "wires", "the design has no contact wire");
  elements_ = mesh.wires[mesh.contact_wire].elements;
  for (int e : elements_) {
    std::array<double, 12> q{};
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 6; ++c) q[6 * a + c] = node_values[6 * mesh.cables[e].nodes[a] + c];
    q_.push_back(q);
    node_x_.push_back(q[0]);
  }
  node_x_.push_back(q_.back()[6]);
  x_begin_ = node_x_.front();
  x_end_ = node_x_.back();
  for (std::size_t i = 1; i < node_x_.size(); ++i)
    if (!(node_x_[i] > node_x_[i - 1]))
      throw InputError(mesh.source_file, "wires",
                       "contact-wire nodes must advance along x (element " +
                           std::to_string(elements_[i - 1]) + ")");
}

bool ContactWireLocator::locate(double x, int& element, double& chi) const {
  if (x < x_begin_ || x > x_end_) return false;
  // Pantographs move steadily: start from the last element found.
  int i = std::clamp(last_, 0, static_cast<int>(elements_.size()) - 1);
  if (!(node_x_[i] <= x && x <= node_x_[i + 1])) {
    auto it = std::upper_bound(node_x_.begin(), node_x_.end(), x);
    i = std::clamp(static_cast<int>(it - node_x_.begin()) - 1, 0,
                   static_cast<int>(elements_.size()) - 1);
  }
  last_ = i;
  element = elements_[i];
  const auto& q = q_[i];
  const Vector12d q12 = Eigen::Map<const Vector12d>(q.data());
  chi = locate_contact_point(q12, mesh_.cables[element].ref_length, x).chi;
  return true;
}

}  // namespace pcsim::contact
