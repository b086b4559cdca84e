// Flexible DSA-380: tube sections (2.29), beam mesh, joints and the map from the rigid
// mechanism to the coordinates.
#include <cmath>
#include <stdexcept>

#include "pcsim/pantograph/flexible_dsa380.hpp"

namespace pcsim::pantograph {
namespace {

enum Point { kP1, kP2, kP3, kP4, kP5, kP6, kPj, kPointCount };
constexpr int kBar8Angle = 6;  // index of bar 8 in Pose::angle (bars 1–6 are 0..5)

// Points and bar angles of the rigid mechanism at frame angle θ (A.1–A.3).
struct Pose {
  std::array<Eigen::Vector2d, kPointCount> point;
  std::array<double, 7> angle{};
};

Pose mechanism_pose(const Dsa380Parameters& p, double theta) {
  const Dsa380Kinematics k = dsa380_kinematics(p, theta);
  if (!k.assembled)
    throw std::invalid_argument("flexible dsa380: the mechanism cannot be assembled at θ = " +
                                std::to_string(theta));
  Pose s;
  s.point[kP1] = {p.x1, p.y1};
  s.point[kP2] = {0.0, 0.0};
  s.point[kP3] = {k.x3[0], k.y3[0]};
  s.point[kP4] = {k.x4[0], k.y4[0]};
  s.point[kP5] = {k.x5[0], k.y5[0]};
  s.point[kP6] = {k.x6[0], k.y6[0]};
  s.point[kPj] = {k.xj[0], k.yj[0]};
  s.angle = {theta, k.theta2[0], k.theta3[0], k.theta4[0], k.theta5[0], k.theta6[0], 0.0};
  const Eigen::Vector2d b8 = s.point[kP6] - s.point[kP4];
  s.angle[kBar8Angle] = std::atan2(b8.y(), b8.x());
  return s;
}

double source_value(const FlexibleDsa380Mesh::Source& src, const Pose& pose,
                    const Eigen::Vector3d& head) {
  using Kind = FlexibleDsa380Mesh::Source::Kind;
  switch (src.kind) {
    case Kind::position:
      return ((1 - src.s) * pose.point[src.a] + src.s * pose.point[src.b])[src.component];
    case Kind::angle:
      return pose.angle[src.a];
    case Kind::head:
      return head[src.component];
  }
  return 0;
}

// One bar of the mesh: end points, the rotation coordinates at its ends (−1: released).
struct BarPlan {
  int bar;  // 1..6, 8
  int start, end;
  int rot_start, rot_end;
  int elements;
};

class MeshBuilder {
 public:
  MeshBuilder(const FlexibleDsa380Parameters& p, const std::array<TubeSection, 9>& sections)
      : p_(p), sections_(sections), pose_(mechanism_pose(p.rigid, p.rigid.theta_guess)) {}

  int add(const std::string& name, FlexibleDsa380Mesh::Source src) {
    mesh_.names.push_back(name);
    mesh_.sources.push_back(src);
    return static_cast<int>(mesh_.names.size()) - 1;
  }
  int add_angle(const std::string& name, int bar_angle) {
    return add(name, {FlexibleDsa380Mesh::Source::Kind::angle, bar_angle, 0, 0, 0.0});
  }
  void add_point(const std::string& name, int point) {
    point_dof_[point][0] =
        add("x" + name, {FlexibleDsa380Mesh::Source::Kind::position, point, point, 0, 0.0});
    point_dof_[point][1] =
        add("y" + name, {FlexibleDsa380Mesh::Source::Kind::position, point, point, 1, 0.0});
  }
  double reference(int dof) const {
    return source_value(mesh_.sources[dof], pose_, Eigen::Vector3d::Zero());
  }
  void add_bar(const BarPlan& b);
  FlexibleDsa380Mesh finish() {
    mesh_.x5 = point_dof_[kP5][0];
    mesh_.y5 = point_dof_[kP5][1];
    return std::move(mesh_);
  }

 private:
  const FlexibleDsa380Parameters& p_;
  const std::array<TubeSection, 9>& sections_;
  Pose pose_;
  FlexibleDsa380Mesh mesh_;
  std::array<std::array<int, 2>, kPointCount> point_dof_{
      {{-1, -1}, {-1, -1}, {-1, -1}, {-1, -1}, {-1, -1}, {-1, -1}, {-1, -1}}};
};

void MeshBuilder::add_bar(const BarPlan& b) {
  const int angle_index = b.bar == 8 ? kBar8Angle : b.bar - 1;
  const double bar_angle = pose_.angle[angle_index];
  const TubeSection& t = sections_[b.bar - 1];
  const double E = p_.youngs_modulus;
  PlanarBeamSection section{E * t.area, E * t.second_moment, p_.density * t.area,
                            p_.density * t.second_moment};
  if (t.mass == 0) section.mass_per_length = section.rotary_inertia_per_length = 0;
  const Eigen::Vector2d Pa = pose_.point[b.start], Pb = pose_.point[b.end];
  const std::string tag = "bar" + std::to_string(b.bar) + ".";
  // Node k: translation and rotation coordinates (interior nodes get their own).
  std::vector<std::array<int, 3>> node(b.elements + 1);
  for (int k = 0; k <= b.elements; ++k) {
    if (k == 0 || k == b.elements) {
      const int pt = k == 0 ? b.start : b.end;
      node[k] = {point_dof_[pt][0], point_dof_[pt][1], k == 0 ? b.rot_start : b.rot_end};
      continue;
    }
    const double s = static_cast<double>(k) / b.elements;
    const std::string n = tag + std::to_string(k) + ".";
    using Kind = FlexibleDsa380Mesh::Source::Kind;
    node[k][0] = add(n + "x", {Kind::position, b.start, b.end, 0, s});
    node[k][1] = add(n + "y", {Kind::position, b.start, b.end, 1, s});
    node[k][2] = add_angle(n + "phi", angle_index);
  }
  for (int k = 0; k < b.elements; ++k) {
    FlexibleDsa380Mesh::Element e;
    e.bar = b.bar;
    e.beam.section = section;
    e.beam.length0 = (Pb - Pa).norm() / b.elements;
    e.beam.hinge_end2 = node[k + 1][2] < 0;
    // Offsets c = φ − β of the stress-free state: nonzero where a rotation coordinate is
    // shared by two pieces of one rigid body (bars 3–4 and 1–8 at point 4).
    e.beam.offset1 = node[k][2] >= 0 ? reference(node[k][2]) - bar_angle : 0.0;
    e.beam.offset2 = node[k + 1][2] >= 0 ? reference(node[k + 1][2]) - bar_angle : 0.0;
    for (int j = 0; j < 2; ++j)
      for (int c = 0; c < 3; ++c) e.dof[3 * j + c] = node[k + j][c];
    const double s0 = static_cast<double>(k) / b.elements, s1 = (k + 1.0) / b.elements;
    e.fixed.segment<2>(0) = (1 - s0) * Pa + s0 * Pb;  // used where a translation is fixed
    e.fixed.segment<2>(3) = (1 - s1) * Pa + s1 * Pb;
    mesh_.elements.push_back(e);
  }
}

}  // namespace

std::array<TubeSection, 9> flexible_dsa380_sections(const FlexibleDsa380Parameters& p) {
  const Dsa380Parameters& g = p.rigid;
  const double bar8 = std::sqrt(g.r * g.r + g.L1 * g.L1 - 2 * g.r * g.L1 * std::cos(g.theta_r));
  const std::array<double, 9> length = {g.L1, g.L2, g.L3, g.L4, g.L5, g.L6, g.L7, bar8, g.L1p};
  std::array<TubeSection, 9> s;
  for (int b = 0; b < 9; ++b) {
    TubeSection& t = s[b];
    t.length = length[b];
    t.r_ext = p.r_ext[b];
    const std::string bar = "flexible dsa380: bar " + std::to_string(b + 1) + ": ";
    if (!(t.r_ext > 0)) throw std::invalid_argument(bar + "external radius must be positive");
    if (b < 7) {
      t.mass = g.m[b];
      const double r2 = t.r_ext * t.r_ext - t.mass / (p.density * M_PI * t.length);  // (2.29)
      if (!(r2 >= 0))
        throw std::invalid_argument(bar + "a steel tube of this external radius is lighter than " +
                                    std::to_string(t.mass) + " kg (2.29)");
      t.r_int = std::sqrt(r2);
    } else {
      t.r_int = p.massless_r_int[b - 7];
      if (!(t.r_int >= 0 && t.r_int < t.r_ext))
        throw std::invalid_argument(bar + "internal radius must be in [0, r_ext)");
    }
    const double ro2 = t.r_ext * t.r_ext, ri2 = t.r_int * t.r_int;
    t.area = M_PI * (ro2 - ri2);
    t.second_moment = M_PI / 4 * (ro2 * ro2 - ri2 * ri2);
  }
  return s;
}

FlexibleDsa380Mesh build_flexible_dsa380_mesh(const FlexibleDsa380Parameters& p,
                                              const std::array<TubeSection, 9>& sections) {
  for (int n : p.elements)
    if (n < 1) throw std::invalid_argument("flexible dsa380: elements per bar must be >= 1");
  MeshBuilder m(p, sections);
  using Kind = FlexibleDsa380Mesh::Source::Kind;
  // The first four coordinates are the rigid model's q = {θ, x10, y10, θ7}.
  const int theta = m.add_angle("theta", 0);
  m.add("x10", {Kind::head, 0, 0, 0, 0.0});
  m.add("y10", {Kind::head, 0, 0, 1, 0.0});
  m.add("theta7", {Kind::head, 0, 0, 2, 0.0});
  const std::pair<const char*, int> joints[] = {
      {"5", kP5}, {"4", kP4}, {"3", kP3}, {"6", kP6}, {"j", kPj}};
  for (const auto& [name, pt] : joints) m.add_point(name, pt);
  const int rot1_4 = m.add_angle("phi1@4", 0);   // bars 1 and 8 (one piece)
  const int rot34_4 = m.add_angle("phi4@4", 3);  // bars 3 and 4 (one piece, angle θ34)
  const int rot2_2 = m.add_angle("phi2@2", 1), rot2_3 = m.add_angle("phi2@3", 1);
  const int rot3_3 = m.add_angle("phi3@3", 2), rot4_5 = m.add_angle("phi4@5", 3);
  const int rot5_6 = m.add_angle("phi5@6", 4), rot5_j = m.add_angle("phi5@j", 4);
  const int rot6_j = m.add_angle("phi6@j", 5), rot6_5 = m.add_angle("phi6@5", 5);
  const auto& n = p.elements;
  m.add_bar({1, kP1, kP4, theta, rot1_4, n[0]});
  m.add_bar({2, kP2, kP3, rot2_2, rot2_3, n[1]});
  m.add_bar({3, kP3, kP4, rot3_3, rot34_4, n[2]});
  m.add_bar({4, kP4, kP5, rot34_4, rot4_5, n[3]});
  m.add_bar({5, kP6, kPj, rot5_6, rot5_j, n[4]});
  m.add_bar({6, kPj, kP5, rot6_j, rot6_5, n[5]});
  m.add_bar({8, kP4, kP6, rot1_4, -1, 1});  // massless, hinged at 6: one element is exact
  return m.finish();
}

Eigen::VectorXd FlexibleDsa380Pantograph::rigid_configuration(double theta, double x10, double y10,
                                                              double theta7) const {
  const Pose pose = mechanism_pose(p_.rigid, theta);
  const Eigen::Vector3d head(x10, y10, theta7);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(dof_count());  // bellows loop state (if any): 0
  for (std::size_t i = 0; i < mesh_.sources.size(); ++i)
    q[i] = source_value(mesh_.sources[i], pose, head);
  return q;
}

}  // namespace pcsim::pantograph
