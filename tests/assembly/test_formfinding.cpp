// Form-finding of the EN 50318 reference catenary (thesis 3.1.3, the
// "constrained equations" method): contact-wire height at every dropper and
// wire tensions against the design, quadratic convergence of the monolithic
// Newton iteration, and the static configuration without form-finding as the
// control that shows form-finding changes the result.
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/scene/design_reader.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/solvers/statics.hpp"

using namespace pcsim;

namespace {

const char* const kReferenceDesign = PCSIM_SOURCE_DIR "/meshes/en50318-reference.yaml";
constexpr double kContactWireHeight = 5.3;     // contact_wire_height of the design, presag 0 [m]
constexpr double kContactTension = 20000.0;    // [N]
constexpr double kMessengerTension = 16000.0;  // [N]
constexpr int kDroppers = 10 * 9;              // 10 spans, 9 droppers each

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

// Largest |z - 5.3 m| over the contact-wire ends of the droppers, computed
// from the node values (independently of StaticResult::max_height_error_m).
double max_dropper_height_error(const catenary::CatenaryMesh& mesh,
                                const std::vector<double>& node_values, int* n_droppers) {
  double worst = 0;
  *n_droppers = 0;
  for (const auto& bar : mesh.bars) {
    if (bar.kind != catenary::BarKind::dropper) continue;
    // The lower end of a dropper is the one on the contact wire.
    const int a = bar.nodes[0], b = bar.nodes[1];
    const int lower = node_values[6 * a + 2] < node_values[6 * b + 2] ? a : b;
    worst = std::max(worst, std::abs(node_values[6 * lower + 2] - kContactWireHeight));
    ++*n_droppers;
  }
  return worst;
}

// Mean axial force of every tension segment (average over its elements of the
// element mean force), recomputed from the node values and the mesh's
// unstressed lengths; returns the largest relative error against the design
// tension of the segment's wire.
double max_segment_tension_error(const catenary::CatenaryMesh& mesh,
                                 const std::vector<double>& node_values) {
  double worst = 0;
  for (const auto& segment : mesh.tension_segments) {
    const auto& wire = mesh.wires[segment.wire];
    const double design =
        wire.kind == catenary::WireKind::contact ? kContactTension : kMessengerTension;
    double sum = 0;
    for (int e : segment.elements) {
      const auto& el = mesh.cables[e];
      catenary::Vec12 q;
      for (int c = 0; c < 6; ++c) {
        q[c] = node_values[6 * el.nodes[0] + c];
        q[6 + c] = node_values[6 * el.nodes[1] + c];
      }
      sum += catenary::cable_mean_axial_force(catenary::cable_section(wire), el.ref_length,
                                              el.unstressed_length, q);
    }
    const double mean = sum / segment.elements.size();
    worst = std::max(worst, std::abs(mean / design - 1.0));
  }
  return worst;
}

}  // namespace

TEST(FormFinding, En50318HeightsTensionsAndQuadraticNewton) {
  const auto mesh = scene::load_catenary_design(kReferenceDesign);
  assembly::CatenarySystem system(PETSC_COMM_WORLD, mesh, assembly::form_finding_unknowns(mesh));
  Vec x = system.create_vector();
  system.design_state(x);
  const auto result = solvers::solve_static(system, x, true);
  VecDestroy(&x);
  ASSERT_TRUE(result.converged) << result.converged_reason;

  // Heights: every dropper, recomputed from the node values.
  int n_droppers = 0;
  const double height_error =
      max_dropper_height_error(system.mesh(), result.node_values, &n_droppers);
  EXPECT_EQ(n_droppers, kDroppers);
  EXPECT_EQ(static_cast<int>(system.mesh().height_targets.size()), kDroppers);
  EXPECT_LE(height_error, 1e-4) << "contact-wire height error at the droppers [m]";
  EXPECT_LE(result.max_height_error_m, 1e-4);
  // Tensions: every segment (contact wire, messenger per span), recomputed
  // with the element kernel from the found unstressed lengths.
  const double tension_error = max_segment_tension_error(system.mesh(), result.node_values);
  EXPECT_LE(tension_error, 1e-3) << "relative wire tension error";
  EXPECT_LE(result.max_tension_error_rel, 1e-3);
  // The found dropper lengths are physical: positive and shorter than the
  // 1.2 m system height.
  for (const auto& bar : system.mesh().bars)
    if (bar.kind == catenary::BarKind::dropper) {
      EXPECT_GT(bar.unstressed_length, 0.0);
      EXPECT_LT(bar.unstressed_length, 1.2);
    }

  // Quadratic convergence. For every Newton step whose new residual norm is
  // above the round-off floor (the iteration stagnates at ~1e-4 N, 7.4e-5 N on
  // this design; steps are judged above 1e-3 N so that rounding cannot decide),
  //   r_{k+1} <= C r_k^2,  C = 2e-4 1/N,
  // and the contraction factor q_k = r_{k+1} / r_k falls by at least 5 from
  // one step to the next (quadratic: q_{k+1} ~ C r_{k+1}; a linearly
  // converging iteration keeps q_k constant and fails both checks).
  const auto& r = result.residual_history;
  constexpr double kFloor = 1e-3, kC = 2e-4;
  ASSERT_GE(r.size(), 3u);
  if (rank_of(PETSC_COMM_WORLD) == 0) {
    std::printf("EN 50318 form-finding: %d Newton iterations, ||R||:", result.snes_iterations);
    for (double v : r) std::printf(" %.3e", v);
    std::printf("\n  max height error %.3e m, max tension error %.3e\n", height_error,
                tension_error);
  }
  int quadratic_checks = 0;
  for (std::size_t k = 0; k + 1 < r.size() && r[k + 1] > kFloor; ++k) {
    if (rank_of(PETSC_COMM_WORLD) == 0)
      std::printf("  step %zu: r_k+1 / r_k^2 = %.3e 1/N, r_k+1 / r_k = %.3e\n", k + 1,
                  r[k + 1] / (r[k] * r[k]), r[k + 1] / r[k]);
    EXPECT_LE(r[k + 1], kC * r[k] * r[k])
        << "step " << k + 1 << ": r_k " << r[k] << ", r_k+1 " << r[k + 1];
    if (k >= 1) EXPECT_LE(r[k + 1] / r[k], 0.2 * r[k] / r[k - 1]) << "step " << k + 1;
    ++quadratic_checks;
  }
  EXPECT_GE(quadratic_checks, 3) << "too few Newton steps above the round-off floor to judge";
  // Converged to the floor.
  EXPECT_LT(r.back(), 1e-3);
}

TEST(FormFinding, DesignLengthsWithoutFormFindingMissTheTargets) {
  // Control: the same design solved with its design lengths (droppers at
  // their geometric length, wires at the first-guess unstressed length).
  // Dropper stretch and the wires' weight move the contact wire far more
  // than the form-finding tolerance; the tensions miss the design too.
  const auto mesh = scene::load_catenary_design(kReferenceDesign);
  assembly::CatenarySystem system(PETSC_COMM_WORLD, mesh);
  Vec x = system.create_vector();
  system.design_state(x);
  const auto result = solvers::solve_static(system, x, false);
  VecDestroy(&x);
  ASSERT_TRUE(result.converged) << result.converged_reason;
  int n_droppers = 0;
  const double height_error =
      max_dropper_height_error(system.mesh(), result.node_values, &n_droppers);
  EXPECT_EQ(n_droppers, kDroppers);
  const double tension_error = max_segment_tension_error(system.mesh(), result.node_values);
  if (rank_of(PETSC_COMM_WORLD) == 0)
    std::printf("EN 50318 without form-finding: max height error %.3e m, max tension error %.3e\n",
                height_error, tension_error);
  // 1 mm and 0.1 % are 10 times and once the form-finding tolerances.
  EXPECT_GT(height_error, 1e-3);
  EXPECT_GT(tension_error, 1e-3);
  EXPECT_NEAR(result.max_height_error_m, height_error, 1e-12);
}
