// Supports of one tension section of a parametric line: the wire ends
// (anchors, tensioning devices, the midpoint anchor), the messenger supports
// and the steady arms (see docs/design-format.md).
#include <cmath>

#include "geometry_line.hpp"
#include "pcsim/catenary/reactions.hpp"

namespace pcsim::catenary::detail {

const MessengerSupportDesign& SectionBuilder::messenger_support(int k) const {
  const MessengerSupportDesign* model = &in_.messenger_supports;
  for (const auto& o : in_.support_overrides)
    for (long s : o.supports)
      if (s == k && o.messenger) model = &*o.messenger;
  return *model;
}

const SteadyArmDesign& SectionBuilder::steady_arm(int k) const {
  const SteadyArmDesign* model = &in_.steady_arms;
  for (const auto& o : in_.support_overrides)
    for (long s : o.supports)
      if (s == k && o.steady_arm) model = &*o.steady_arm;
  return *model;
}

// Mass whose weight the steady arm hangs on the wire: a hinged arm carries
// half its own (the other half on the pivot).
double SectionBuilder::steady_arm_weight_mass(int k) const {
  const SteadyArmDesign& arm = steady_arm(k);
  return arm.model == SteadyArmModel::hinged ? 0.5 * arm.mass : arm.mass;
}

// Wire ends held (x, y, z; a tensioning device released after the static
// solution), the messenger on its supports, the contact wire on its steady
// arms; a midpoint anchor when both ends hang on balance weights.
void SectionBuilder::add_supports() {
  const auto& sec = geo_.layout();
  for (int k = sec.first; k <= sec.last; ++k) {
    const int i = support_station_[k - sec.first];
    const int c = base_ + i, m = base_ + S_ + i;
    if (k == sec.first || k == sec.last) {
      for (int dof = 0; dof < 3; ++dof)
        mesh_.nodes[m].fixed[dof] = mesh_.nodes[c].fixed[dof] = true;
      if (geo_.role(k) != Role::anchor && steady_arm(k).mass > 0)
        mesh_.point_masses.push_back({c, steady_arm(k).mass, "steady_arm"});
      add_tensioning_device(k, c, contact_wire_, in_.contact.tension);
      add_tensioning_device(k, m, messenger_wire_, in_.messenger.tension);
      continue;
    }
    add_messenger_support(k, m);
    if (geo_.role(k) == Role::raised) {
      // Out of service: the cantilever holds the wire (laterally and
      // vertically) on its way to the anchor.
      mesh_.registrations.push_back({c, k, geo_.track_normal(k)});
      hold_laterally(k, c);
      mesh_.nodes[c].fixed[2] = true;
      continue;
    }
    add_steady_arm(k, c);
  }
  if (in_.tensioning.device != TensioningDeviceKind::weight) return;
  // Midpoint anchor: the contact wire's x held at the inner support nearest
  // the middle of the section's own stretch.
  int mid = -1;
  for (int k = sec.first + 1; k < sec.last; ++k)
    if (geo_.role(k) == Role::service &&
        (mid < 0 || std::abs(2 * k - sec.own_first - sec.own_last) <
                        std::abs(2 * mid - sec.own_first - sec.own_last)))
      mid = k;
  if (mid < 0)
    throw InputError(
        in_.file,
        in_.sections.empty() ? "spans.count" : "sections[" + std::to_string(section_) + "].spans",
        "a section tensioned by balance weights at both ends needs an inner support "
        "for its midpoint anchor");
  mesh_.nodes[base_ + support_station_[mid - sec.first]].fixed[0] = true;
}

void SectionBuilder::add_tensioning_device(int k, int node, int wire, double tension) {
  const TensioningDesign& t = in_.tensioning;
  if (t.device == TensioningDeviceKind::fixed) return;
  TensioningDevice dev;
  dev.node = node;
  dev.wire = wire;
  dev.direction = (k == geo_.layout().first ? -1.0 : 1.0) * geo_.track_tangent(k);
  dev.travel = t.travel;
  if (t.device == TensioningDeviceKind::weight) {
    dev.kind = TensioningKind::weight;
    const double g = mesh_.gravity.norm();
    const double weight = t.weight_mass ? *t.weight_mass : (g > 0 ? tension / (g * t.ratio) : 0.0);
    dev.mass = weight * t.ratio * t.ratio;  // the weight moves ratio x the wire end
  } else {
    dev.kind = TensioningKind::spring;
    dev.stiffness = t.stiffness;
  }
  mesh_.tensioning_devices.push_back(dev);
}

void SectionBuilder::add_messenger_support(int k, int node) {
  const MessengerSupportDesign& s = messenger_support(k);
  Node& n = mesh_.nodes[node];
  n.fixed[0] = n.fixed[1] = true;
  if (s.model == MessengerSupportModel::fixed) {
    n.fixed[2] = true;
    return;
  }
  mesh_.springs.push_back({node, 2, s.stiffness, Eigen::Vector3d::Zero()});
  if (s.model == MessengerSupportModel::spring_mass && s.mass > 0)
    mesh_.point_masses.push_back({node, s.mass, "messenger_support"});
}

// The registration's lateral constraint: the y DOF where the track normal is
// y, else a stiff horizontal spring along the normal (curved track).
void SectionBuilder::hold_laterally(int k, int node) {
  const Eigen::Vector3d n = geo_.track_normal(k);
  if (std::abs(n.x()) < 1e-12)
    mesh_.nodes[node].fixed[1] = true;
  else
    mesh_.springs.push_back({node, 0, kGuideStiffness, n});
}

void SectionBuilder::add_steady_arm(int k, int node) {
  const SteadyArmDesign& arm = steady_arm(k);
  mesh_.registrations.push_back({node, k, geo_.track_normal(k)});
  if (arm.model == SteadyArmModel::hinged) {
    add_hinged_arm(k, node, arm);
    return;
  }
  hold_laterally(k, node);
  if (arm.model == SteadyArmModel::spring)
    mesh_.springs.push_back({node, 2, arm.stiffness, Eigen::Vector3d::Zero()});
  if (arm.mass > 0) mesh_.point_masses.push_back({node, arm.mass, "steady_arm"});
}

// A hinged arm: a bar from a fixed pivot, placed horizontally on the side the
// wire's design pull points away from (the arm in tension), to the wire.
// Its mass m as a rigid bar rotating about the pivot: inertia m/3 and weight
// m/2 at the wire (a point mass m/3 and a node force m/6 g).
void SectionBuilder::add_hinged_arm(int k, int node, const SteadyArmDesign& arm) {
  const Eigen::Vector3d here = mesh_.nodes[node].position;
  const Eigen::Vector3d before = geo_.contact(k - 1, 0.0), after = geo_.contact(k, L_);
  Eigen::Vector3d pull =
      unit(Eigen::Vector3d(after - here)) - unit(Eigen::Vector3d(here - before));  // / tension
  pull.z() = 0;
  Eigen::Vector3d dir =
      pull.norm() > 1e-6 ? Eigen::Vector3d(-pull.normalized()) : geo_.track_normal(k);
  Node pivot;
  pivot.position = here + arm.length * dir;
  pivot.fixed = {true, true, true, false, false, false};
  const int p = static_cast<int>(mesh_.nodes.size());
  mesh_.nodes.push_back(pivot);
  BarElement b;
  b.nodes = {p, node};
  b.kind = BarKind::steady_arm;
  b.stiffness = arm.axial_stiffness;
  b.unstressed_length = arm.length;
  b.slack = SlackCriterion::none;
  mesh_.bars.push_back(b);
  if (arm.mass > 0) {
    mesh_.point_masses.push_back({node, arm.mass / 3.0, "steady_arm"});
    mesh_.node_forces.push_back({node, (arm.mass / 6.0) * mesh_.gravity, "steady_arm_weight"});
  }
}

}  // namespace pcsim::catenary::detail
