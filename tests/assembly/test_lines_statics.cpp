// Static configuration of real lines (parametric generator): form-finding
// over overlaps (both wires at their design heights), the tensioning devices
// released with the static configuration still in equilibrium, stitched
// catenary form-finding and elasticity, a prescribed irregularity carried by
// the static wire, pull-off forces on straight and curved track, and the
// tangents of the new terms against finite differences.
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../catenary/design_fixtures.hpp"
#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/catenary/geometry.hpp"
#include "pcsim/catenary/reactions.hpp"
#include "pcsim/scene/design_reader.hpp"
#include "pcsim/simulation/elasticity.hpp"
#include "pcsim/simulation/statics.hpp"
#include "pcsim/solvers/statics.hpp"

using namespace pcsim;
using catenary::CatenaryMesh;

namespace {

int rank() {
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

double norm(Vec x) {
  PetscReal n;
  PCSIM_PETSC(VecNorm(x, NORM_2, &n));
  return n;
}

// Residual norm of the static problem of 'mesh' (no form-finding) at node values v.
double static_residual(const CatenaryMesh& mesh, const std::vector<double>& v) {
  assembly::CatenarySystem system(PETSC_COMM_WORLD, mesh);
  Vec x = system.create_vector(), R = system.create_vector();
  assembly::set_state_from_node_values(system, v, x);
  system.load_state(x);
  system.assemble_static(R, nullptr);
  const double r = norm(R);
  VecDestroy(&x);
  VecDestroy(&R);
  return r;
}

// Mean axial force of the two contact-wire elements at a node.
double support_tension(const CatenaryMesh& m, const std::vector<double>& v, int node) {
  double sum = 0;
  int n = 0;
  for (const auto& el : m.cables) {
    if (el.nodes[0] != node && el.nodes[1] != node) continue;
    catenary::Vec12 q;
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 6; ++c) q[6 * a + c] = v[6 * el.nodes[a] + c];
    sum += catenary::cable_mean_axial_force(catenary::cable_section(m.wires[el.wire], el),
                                            el.ref_length, el.unstressed_length, q);
    ++n;
  }
  return sum / n;
}

// Non-uniformity (max - min) / (max + min) of an elasticity curve.
double non_uniformity(const std::vector<double>& u) {
  const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
  return (*hi - *lo) / (*hi + *lo);
}

}  // namespace

TEST(LineStatics, OverlapWiresAtDesignHeightsAndDevicesInEquilibrium) {
  const auto design =
      scene::load_catenary_design(PCSIM_SOURCE_DIR "/meshes/lines/three-sections-short.yaml");
  const auto st = simulation::static_configuration(PETSC_COMM_WORLD, design, true);
  const auto& v = st.result.node_values;
  // Both wires over both overlaps: every target of every contact wire
  // (independently of StaticResult), and at least 5 of each wire inside
  // each overlap. Form-finding meets a height row exactly up to round-off
  // (measured 0 on 5.3 m heights); 1e-9 m leaves room for rank counts.
  double worst = 0;
  for (std::size_t z = 0; z < design.zones.size(); ++z) {
    const auto& zone = design.zones[z];
    if (!zone.overlap) continue;
    const std::size_t j = z / 2;  // zones: section 1, overlap 1-2, section 2, ...
    for (int w : {design.contact_wires[j], design.contact_wires[j + 1]}) {
      int inside = 0;
      for (const auto& t : design.height_targets) {
        const double x = design.nodes[t.node].position.x();
        if (x < zone.from_x || x > zone.to_x) continue;
        if (std::count(design.wires[w].nodes.begin(), design.wires[w].nodes.end(), t.node) == 0)
          continue;
        ++inside;
        worst = std::max(worst, std::abs(v[6 * t.node + 2] - t.z));
      }
      EXPECT_GE(inside, 5) << design.wires[w].name << " in " << zone.name;
    }
  }
  EXPECT_LE(worst, 1e-9);
  EXPECT_LE(st.result.max_height_error_m, 1e-9);
  EXPECT_LE(st.result.max_tension_error_rel, 1e-9);  // measured 2e-12
  // Every device released, pulling with about its wire's tension: the
  // horizontal reaction of the anchor, T cos(slope) with the bending shear
  // (measured within 2e-4 of T).
  ASSERT_EQ(st.mesh.tensioning_devices.size(), 12u);
  for (const auto& dev : st.mesh.tensioning_devices) {
    EXPECT_TRUE(dev.released);
    EXPECT_FALSE(st.mesh.nodes[dev.node].fixed[0]);
    EXPECT_NEAR(dev.pull / st.mesh.wires[dev.wire].tension, 1.0, 1e-3);
  }
  // The released model (free ends, their forces, the weights' masses) has
  // the static configuration as its equilibrium: its residual there is the
  // form-finding's (Newton floor ~1e-4 N on a 1e4 N scale).
  const double r_released = static_residual(st.mesh, v);
  if (rank() == 0) std::printf("  released devices: static residual %.2e N\n", r_released);
  EXPECT_LT(r_released, 1e-3);
}

TEST(LineStatics, StitchedFormFindingAndMoreUniformElasticity) {
  auto stitched = design_fixtures::reference_design(4);
  stitched.element_length = 1.0;
  auto plain = stitched;
  stitched.stitch_wire = catenary::StitchWireDesign{18.0, 3500.0, 0.31, 4.2e6};
  std::vector<double> xs;
  for (double x = 60.0; x <= 120.0 + 1e-9; x += 5.0) xs.push_back(x);  // span 2, supports included
  std::vector<double> nonuniform;
  for (const auto* d : {&stitched, &plain}) {
    const auto st = simulation::static_configuration(
        PETSC_COMM_WORLD, catenary::build_parametric(*d), true, "lines_");
    // Form-finding errors as for the simple catenary (the stitch wires'
    // tension segments included). Newton stops once ||R||_2 < 1e-8 of the
    // loads (solvers/statics.hpp): here at 2.6e-5 N, which leaves tension
    // errors of 1.3e-9 (stitched; 2e-12 after one more, rounding-bound step).
    EXPECT_LE(st.result.max_height_error_m, 1e-9);
    EXPECT_LE(st.result.max_tension_error_rel, 1e-8);
    const auto e = simulation::static_elasticity(PETSC_COMM_WORLD, st, xs, 100.0);
    nonuniform.push_back(non_uniformity(e.uplift));
    if (rank() == 0) {
      std::printf("  %s: uplift per 100 N [mm]:", d == &stitched ? "stitched" : "simple");
      for (double u : e.uplift) std::printf(" %.1f", 1e3 * u);
      std::printf("  non-uniformity %.1f %%\n", 100 * nonuniform.back());
    }
    if (d == &stitched) {
      int stitch_segments = 0;
      for (std::size_t s = 0; s < st.mesh.tension_segments.size(); ++s)
        if (!st.mesh.tension_segments[s].bars.empty()) {
          ++stitch_segments;
          EXPECT_NEAR(st.result.segment_tensions[s], 3500.0, 1e-8 * 3500.0);  // measured 1.3e-9
        }
      EXPECT_EQ(stitch_segments, 3);
    }
  }
  // The known result: stitching makes the elasticity more uniform (measured
  // 16 % against 34 % on the 10-span designs of meshes/lines): less than
  // two thirds of the simple catenary's.
  EXPECT_LT(nonuniform[0], 2.0 / 3.0 * nonuniform[1]);
}

TEST(LineStatics, PrescribedProfileAtTheDroppersAndBetween) {
  auto d = design_fixtures::reference_design(4);
  d.element_length = 1.0;
  const auto plain = simulation::static_configuration(
      PETSC_COMM_WORLD, catenary::build_parametric(d), true, "lines_");
  // A 30 m wave of 2 mm over spans 2-3, sampled every 0.25 m.
  for (double x = 60.0; x <= 180.0 + 1e-9; x += 0.25) {
    d.irregularities.profile_x.push_back(x);
    d.irregularities.profile_dz.push_back(0.002 * std::sin(2 * M_PI * (x - 60.0) / 30.0));
  }
  const auto mesh = catenary::build_parametric(d);
  const auto st = simulation::static_configuration(PETSC_COMM_WORLD, mesh, true, "lines_");
  auto dz = [](double x) {
    return x < 60.0 || x > 180.0 ? 0.0 : 0.002 * std::sin(2 * M_PI * (x - 60.0) / 30.0);
  };
  // At the droppers the static wire carries the profile: the issue asks for
  // 0.1 mm; form-finding gives it to round-off (1e-9 m asserted).
  double at_droppers = 0;
  for (const auto& t : mesh.height_targets) {
    const double x = mesh.nodes[t.node].position.x();
    at_droppers = std::max(at_droppers, std::abs(st.result.node_values[6 * t.node + 2] -
                                                 plain.result.node_values[6 * t.node + 2] - dz(x)));
  }
  // Between them the contact sees the static wire plus the contact-gap
  // offset dz - (dz interpolated between the droppers); the static wire
  // follows that interpolation up to its bending boundary layers
  // (sqrt(EI/T) = 0.1 m): 0.05 mm asserted.
  const auto& g = mesh.contact_gap_offsets.at(0);
  double between = 0;
  for (int n : mesh.wires[0].nodes) {
    const double x = mesh.nodes[n].position.x();
    const auto it = std::lower_bound(g.x.begin(), g.x.end(), x);
    if (it == g.x.begin() || it == g.x.end()) continue;
    const std::size_t i = it - g.x.begin();
    const double w = (x - g.x[i - 1]) / (g.x[i] - g.x[i - 1]);
    const double offset = (1 - w) * g.offset[i - 1] + w * g.offset[i];
    const double seen = st.result.node_values[6 * n + 2] + offset;
    between = std::max(between, std::abs(seen - plain.result.node_values[6 * n + 2] - dz(x)));
  }
  if (rank() == 0)
    std::printf(
        "  profile: error at the droppers %.2e m, seen by the contact between them %.2e m\n",
        at_droppers, between);
  EXPECT_LT(at_droppers, 1e-9);
  EXPECT_LT(between, 5e-5);
}

// Wear in the static solution: the 20 m taut string (40 elements, ends
// pinned) with its right half worn to f = 0.6 of the section
// (CableElement::section_factor, as irregularities.wear sets it). EA scales
// with f: without gravity the string takes one tension T, each element
// stretching to lambda with f EA (lambda^2 - 1) lambda / 2 = T (elements.hpp)
// and the stretched lengths filling the 20 m. The mass scales with f: under
// gravity the ends carry the weight g mu 10 (1 + f), split by moments as
// g mu 20 (3 + f) / 8 left and g mu 20 (1 + 3 f) / 8 right.
TEST(LineStatics, WornStretchIsSofterAndLighter) {
  catenary::CatenaryMesh m = catenary::build_explicit(design_fixtures::taut_string_design());
  const double f = 0.6, EA = 1.44e7, mu = 1.35, g = 9.81, L = 20.0;
  for (auto& el : m.cables)
    if (m.nodes[el.nodes[0]].position.x() >= 10.0 - 1e-9) el.section_factor = f;
  // Exact tension: Newton on T, with lambda(T) of every element by Newton.
  auto lambda = [](double T, double k) {
    double l = 1.0 + T / k;
    for (int it = 0; it < 50; ++it)
      l -= (0.5 * k * (l * l * l - l) - T) / (0.5 * k * (3 * l * l - 1));
    return l;
  };
  auto length = [&](double T) {
    double sum = 0;
    for (const auto& el : m.cables) sum += el.unstressed_length * lambda(T, el.section_factor * EA);
    return sum;
  };
  double T = 2e4;
  for (int it = 0; it < 50; ++it)
    T -= (length(T) - L) / ((length(T + 1.0) - length(T - 1.0)) / 2.0);
  double left_L0 = 0;  // unstressed length of the unworn half
  for (const auto& el : m.cables)
    if (el.section_factor == 1.0) left_L0 += el.unstressed_length;
  const auto st = simulation::static_configuration(PETSC_COMM_WORLD, m, false, "lines_");
  const auto& v = st.result.node_values;
  int middle = -1;
  for (int n : m.wires[0].nodes)
    if (std::abs(m.nodes[n].position.x() - 10.0) < 1e-9) middle = n;
  ASSERT_GE(middle, 0);
  const double tension = support_tension(st.mesh, v, middle);
  if (rank() == 0)
    std::printf("  worn half: T %.6f N (exact %.6f), middle node at %.9f m (exact %.9f)\n", tension,
                T, v[6 * middle], left_L0 * lambda(T, EA));
  // About 15 kN instead of 20 kN (unworn: 20 kN); the worn half stretches
  // 1/f times more. The exact solution has a slope jump at 10 m that the C1
  // cable element cannot follow: the two elements there share one slope,
  // which shifts the middle node by about a strain jump (7e-4) times an
  // element length over ~20 (1.9e-5 m measured) and the tension by that
  // shift over the total stretch of 0.028 m (3.7e-4 measured): 5e-5 m and
  // 1e-3 asserted, well inside the 25 % the wear makes.
  EXPECT_NEAR(tension / T, 1.0, 1e-3);
  EXPECT_NEAR(v[6 * middle], left_L0 * lambda(T, EA), 5e-5);
  EXPECT_LT(T, 0.8 * 2e4);
  // Under gravity: the vertical reactions.
  m.gravity = {0.0, 0.0, -g};
  const auto heavy = simulation::static_configuration(PETSC_COMM_WORLD, m, false, "lines_");
  const int a = m.wires[0].nodes.front(), b = m.wires[0].nodes.back();
  const auto R = catenary::support_forces(heavy.mesh, heavy.result.node_values, {a, b});
  // Mass per unstressed length (the wire as bought): each half weighs
  // g mu f L0 of its elements.
  double worn_L0 = 0;
  for (const auto& el : m.cables)
    if (el.section_factor != 1.0) worn_L0 += el.unstressed_length;
  const double W1 = g * mu * left_L0, W2 = g * mu * f * worn_L0;
  const double weight = W1 + W2;
  if (rank() == 0)
    std::printf("  worn half under gravity: reactions %.6f + %.6f N (weight %.6f N)\n", R[0].z(),
                R[1].z(), weight);
  // The sum is the weight to Newton's floor (1e-8 asserted, relative). The
  // split assumes the loads at their design stations: the worn half's extra
  // stretch moves them by up to 4 mm in 20 m, 2e-4 of the moment (1.6e-4
  // and 2.1e-4 measured): 1e-3.
  EXPECT_NEAR((R[0].z() + R[1].z()) / weight, 1.0, 1e-8);
  EXPECT_NEAR(R[0].z() / (0.75 * W1 + 0.25 * W2), 1.0, 1e-3);
  EXPECT_NEAR(R[1].z() / (0.25 * W1 + 0.75 * W2), 1.0, 1e-3);
}

TEST(LineStatics, PullOffForcesOnStraightAndCurvedTrack) {
  // Droppers vertical in plan (messenger staggered like the contact wire):
  // the contact wire is straight in plan between its registrations, so each
  // steady arm takes the wire's tension there times the change of direction,
  // F = -T_k (t_right - t_left) . n, T_k the mean axial force of the two
  // elements at the support (it differs from the span's mean tension by the
  // droppers' pull along the track, up to 0.5 %).
  for (const double radius : {0.0, 800.0}) {
    auto d = design_fixtures::reference_design(5);
    d.element_length = 1.0;
    d.messenger_stagger = d.stagger;
    if (radius != 0) d.sections = {{5, radius}};
    const auto st = simulation::static_configuration(PETSC_COMM_WORLD,
                                                     catenary::build_parametric(d), true, "lines_");
    const auto& m = st.mesh;
    const auto& f = st.result.registration_forces;
    ASSERT_EQ(f.size(), 4u);
    double worst = 0;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const int k = m.registrations[i].support;
      auto plan = [&](int s) { return Eigen::Vector3d(m.nodes[m.support_nodes[s]].position); };
      Eigen::Vector3d tl = plan(k) - plan(k - 1), tr = plan(k + 1) - plan(k);
      tl.z() = tr.z() = 0;
      const double tension = support_tension(m, st.result.node_values, m.support_nodes[k]);
      const double expected =
          -tension * (tr.normalized() - tl.normalized()).dot(m.registrations[i].lateral);
      worst = std::max(worst, std::abs(f[i] / expected - 1.0));
      if (rank() == 0)
        std::printf("  R = %g m, support %d: pull-off %.2f N, T x angle %.2f N\n", radius, k, f[i],
                    expected);
    }
    // Measured 0.49 % (straight) and 0.46 % (R = 800 m): the C1 cable
    // elements cannot kink at the registration; the wire leaves it at the
    // mean slope and bends over the next elements (0.9 mm off the chord with
    // 1 m elements, 0.3 % of the force with 0.25 m). 1 % asserted.
    EXPECT_LT(worst, 1e-2) << "radius " << radius;
  }
}

TEST(LineStatics, TangentsOfSpringsNodeForcesArmsAndDevices) {
  // A curved section (registrations along the normal), hinged arms, one
  // spring arm, messenger supports on springs, spring tensioning devices
  // (released: free ends, guides across the line, node forces).
  auto d = design_fixtures::reference_design(3);
  d.element_length = 2.0;
  d.sections = {{3, 400.0}};
  d.messenger_supports = {catenary::MessengerSupportModel::spring_mass, 2.0e6, 8.0};
  d.steady_arms = {catenary::SteadyArmModel::hinged, 1.5, 1.2, 1.0e7, 0.0};
  catenary::SupportOverride o;
  o.supports = {2};
  o.steady_arm = catenary::SteadyArmDesign{catenary::SteadyArmModel::spring, 1.0, 1.0, 1e7, 3000.0};
  d.support_overrides = {o};
  d.tensioning = {catenary::TensioningDeviceKind::spring, 1.0, std::nullopt, 2.0e5};
  const auto st = simulation::static_configuration(PETSC_COMM_WORLD, catenary::build_parametric(d),
                                                   true, "lines_");
  assembly::CatenarySystem system(PETSC_COMM_WORLD, st.mesh);
  Vec x = system.create_vector(), dir = system.create_vector(), Rp = system.create_vector(),
      Rm = system.create_vector(), Jd = system.create_vector();
  assembly::set_state_from_node_values(system, st.result.node_values, x);
  PetscRandom rng;
  PCSIM_PETSC(PetscRandomCreate(PETSC_COMM_WORLD, &rng));
  PCSIM_PETSC(PetscRandomSetInterval(rng, -1.0, 1.0));
  PCSIM_PETSC(VecSetRandom(dir, rng));
  PCSIM_PETSC(VecAXPY(x, 1e-4, dir));  // away from the static state
  PCSIM_PETSC(VecSetRandom(dir, rng));
  Mat J = system.layout().create_matrix();
  system.insert_element_pattern(J);
  PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  system.load_state(x);
  PCSIM_PETSC(MatZeroEntries(J));
  system.assemble_static(Rp, J);
  PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatMult(J, dir, Jd));
  // Central differences with h = 1e-6: truncation ~h^2, round-off ~1e-16
  // |F| / h with |F| up to 1e9 N/m x 1e-4 m (the guides): both < 1e-7.
  const double h = 1e-6;
  for (int side = 0; side < 2; ++side) {
    Vec xs;
    PCSIM_PETSC(VecDuplicate(x, &xs));
    PCSIM_PETSC(VecWAXPY(xs, side == 0 ? h : -h, dir, x));
    system.load_state(xs);
    system.assemble_static(side == 0 ? Rp : Rm, nullptr);
    PCSIM_PETSC(VecDestroy(&xs));
  }
  PCSIM_PETSC(VecAXPY(Rp, -1.0, Rm));
  PCSIM_PETSC(VecScale(Rp, 0.5 / h));
  const double jd = norm(Jd);
  PCSIM_PETSC(VecAXPY(Rp, -1.0, Jd));
  const double err = norm(Rp) / jd;
  if (rank() == 0) std::printf("  tangent vs finite differences: relative error %.2e\n", err);
  EXPECT_LT(err, 1e-6);
  EXPECT_GT(st.mesh.node_forces.size(), 0u);
  for (Vec* v : {&x, &dir, &Rp, &Rm, &Jd}) VecDestroy(v);
  MatDestroy(&J);
  PetscRandomDestroy(&rng);
}

TEST(LineStatics, FormFindingTangentWithStitchWireSegments) {
  auto d = design_fixtures::reference_design(3);
  d.element_length = 2.0;
  d.stitch_wire = catenary::StitchWireDesign{18.0, 3500.0, 0.31, 4.2e6};
  const auto mesh = catenary::build_parametric(d);
  assembly::CatenarySystem system(PETSC_COMM_WORLD, mesh, assembly::form_finding_unknowns(mesh));
  assembly::StaticProblem problem(system, true);
  Vec x = system.create_vector(), dir = system.create_vector(), Rp = system.create_vector(),
      Rm = system.create_vector(), Jd = system.create_vector();
  system.design_state(x);
  problem.initial_guess(x);
  PetscRandom rng;
  PCSIM_PETSC(PetscRandomCreate(PETSC_COMM_WORLD, &rng));
  PCSIM_PETSC(PetscRandomSetInterval(rng, -1.0, 1.0));
  PCSIM_PETSC(VecSetRandom(dir, rng));
  PCSIM_PETSC(VecAXPY(x, 1e-5, dir));
  PCSIM_PETSC(VecSetRandom(dir, rng));
  Mat J = problem.create_matrix();
  problem.jacobian(x, J);
  PCSIM_PETSC(MatMult(J, dir, Jd));
  const double h = 1e-7;  // the length scales are ~1: a 1e-7 step keeps 9 digits
  Vec xs;
  PCSIM_PETSC(VecDuplicate(x, &xs));
  PCSIM_PETSC(VecWAXPY(xs, h, dir, x));
  problem.residual(xs, Rp);
  PCSIM_PETSC(VecWAXPY(xs, -h, dir, x));
  problem.residual(xs, Rm);
  PCSIM_PETSC(VecAXPY(Rp, -1.0, Rm));
  PCSIM_PETSC(VecScale(Rp, 0.5 / h));
  const double jd = norm(Jd);
  PCSIM_PETSC(VecAXPY(Rp, -1.0, Jd));
  const double err = norm(Rp) / jd;
  if (rank() == 0)
    std::printf("  form-finding tangent (stitch segments): relative error %.2e\n", err);
  EXPECT_LT(err, 1e-6);
  for (Vec* v : {&x, &dir, &Rp, &Rm, &Jd, &xs}) VecDestroy(v);
  MatDestroy(&J);
  PetscRandomDestroy(&rng);
}
