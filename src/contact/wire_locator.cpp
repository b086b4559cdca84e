#include "pcsim/contact/wire_locator.hpp"

#include <algorithm>
#include <cmath>

#include "pcsim/contact/contact_kernel.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::contact {

using catenary::CatenaryMesh;

ContactWireLocator::ContactWireLocator(const CatenaryMesh& mesh,
                                       const std::vector<double>& node_values, int wire)
    : mesh_(mesh), wire_(wire) {
  if (wire < 0 || wire >= static_cast<int>(mesh.wires.size()))
    throw InputError(mesh.source_file, "wires", "the design has no contact wire");
  elements_ = mesh.wires[wire].elements;
  const auto station = [&](const std::array<double, 12>& q, int node) {
    return mesh.track.station({q[6 * node], q[6 * node + 1]});
  };
  for (int e : elements_) {
    std::array<double, 12> q{};
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 6; ++c) q[6 * a + c] = node_values[6 * mesh.cables[e].nodes[a] + c];
    q_.push_back(q);
    node_x_.push_back(station(q, 0));
  }
  node_x_.push_back(station(q_.back(), 1));
  x_begin_ = node_x_.front();
  x_end_ = node_x_.back();
  for (std::size_t i = 1; i < node_x_.size(); ++i)
    if (!(node_x_[i] > node_x_[i - 1]))
      throw InputError(mesh.source_file, "wires",
                       "contact wire '" + mesh.wires[wire].name +
                           "': its nodes must advance along the track (element " +
                           std::to_string(elements_[i - 1]) + ")");
}

// chi of element i where station(r(chi)) = x on curved track: regula falsi
// (Illinois) on the bracket [0, Lref]; the station is monotone along an
// element.
double ContactWireLocator::curved_chi(int i, double x) const {
  const double lref = mesh_.cables[elements_[i]].ref_length;
  const Vector12d q = Eigen::Map<const Vector12d>(q_[i].data());
  auto g = [&](double chi) {
    return mesh_.track.station({interpolate(q, chi, lref, 0), interpolate(q, chi, lref, 1)}) - x;
  };
  double a = 0, b = lref, ga = node_x_[i] - x, gb = node_x_[i + 1] - x;
  if (ga >= 0) return 0.0;
  if (gb <= 0) return lref;
  int side = 0;
  double c = a;
  for (int it = 0; it < 100 && b - a > 1e-13 * lref; ++it) {
    c = (a * gb - b * ga) / (gb - ga);
    const double gc = g(c);
    if (std::abs(gc) < 1e-13) break;
    if ((gc > 0) == (gb > 0)) {
      b = c, gb = gc;
      if (side == 1) ga *= 0.5;
      side = 1;
    } else {
      a = c, ga = gc;
      if (side == -1) gb *= 0.5;
      side = -1;
    }
  }
  return c;
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
  if (!mesh_.track.straight()) {
    chi = curved_chi(i, x);
    return true;
  }
  const auto& q = q_[i];
  const Vector12d q12 = Eigen::Map<const Vector12d>(q.data());
  chi = locate_contact_point(q12, mesh_.cables[element].ref_length, x).chi;
  return true;
}

}  // namespace pcsim::contact
