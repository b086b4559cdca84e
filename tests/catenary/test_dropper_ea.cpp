// Droppers given by their axial rigidity EA [N] ('droppers.EA', issue 24):
// each dropper's k = EA / L0 follows its own unstressed length (the design
// length, then the form-found one), for one EA or one per dropper position;
// the N/m key 'droppers.stiffness' is unchanged; the error cases.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "../scene/design_test_helpers.hpp"
#include "design_fixtures.hpp"
#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/scene/design_reader.hpp"
#include "pcsim/solvers/statics.hpp"

using namespace pcsim;
using namespace pcsim::catenary;
using namespace pcsim::scene;
using namespace pcsim::design_test;

namespace {

const std::string kStiffnessLine = "stiffness: 1.0e5";
const std::vector<double> kPerPosition = {1.1e5, 1.2e5, 1.3e5, 1.4e5, 1.5e5,
                                          1.6e5, 1.7e5, 1.8e5, 1.9e5};

// The EN 50318 reference design on 2 spans, its dropper stiffness line
// replaced by 'replacement'.
std::string design_with(const std::string& replacement) {
  std::string text = replace_once(reference_text(), "spans: {count: 10,", "spans: {count: 2,");
  return replace_once(text, kStiffnessLine, replacement);
}

std::string per_position_text(const std::vector<double>& values) {
  std::string list = "EA: [";
  for (std::size_t i = 0; i < values.size(); ++i)
    list += (i ? ", " : "") + std::to_string(values[i]);
  return list + "]";
}

std::vector<const BarElement*> droppers_of(const CatenaryMesh& m) {
  std::vector<const BarElement*> out;
  for (const auto& b : m.bars)
    if (b.kind == BarKind::dropper) out.push_back(&b);
  return out;
}

double design_length(const CatenaryMesh& m, const BarElement& b) {
  return (m.nodes[b.nodes[1]].position - m.nodes[b.nodes[0]].position).norm();
}

// |a/b - 1| (a, b > 0).
double rel(double a, double b) {
  return std::abs(a / b - 1.0);
}

}  // namespace

// ------------------------------------------------------------ design ----

TEST(DropperEA, OneEAGivesEachDropperEAOverItsLength) {
  const double EA = 1.0e5;
  const CatenaryMesh m = build_text(design_with("EA: 1.0e5"));
  const auto droppers = droppers_of(m);
  ASSERT_EQ(droppers.size(), 18u);
  double shortest = 1e9, longest = 0;
  for (const BarElement* b : droppers) {
    const double L = design_length(m, *b);
    EXPECT_DOUBLE_EQ(b->axial_rigidity, EA);
    EXPECT_DOUBLE_EQ(b->unstressed_length, L);
    EXPECT_LT(rel(b->stiffness, EA / L), 1e-15);
    EXPECT_LT(rel(bar_parameters(*b).stiffness, EA / L), 1e-15);
    shortest = std::min(shortest, L);
    longest = std::max(longest, L);
  }
  // Droppers of a span differ in length (mid-span ~0.5 m, at the supports
  // ~1.0 m), so their stiffnesses differ by the same factor.
  EXPECT_GT(longest / shortest, 1.5);
  const BarElement* first = droppers.front();  // span 0, dropper 0 (5 m)
  const BarElement* mid = droppers[4];         // span 0, dropper 4 (30 m)
  ASSERT_EQ(first->index_in_span, 0);
  ASSERT_EQ(mid->index_in_span, 4);
  EXPECT_GT(first->unstressed_length, 1.5 * mid->unstressed_length);
  EXPECT_LT(rel(first->stiffness * first->unstressed_length, EA), 1e-15);
  EXPECT_LT(rel(mid->stiffness * mid->unstressed_length, EA), 1e-15);
  EXPECT_GT(mid->stiffness, 1.5 * first->stiffness);
  EXPECT_EQ(mesh_consistency_error(m), "");
}

TEST(DropperEA, ListMapsToDropperPositions) {
  const CatenaryMesh m = build_text(design_with(per_position_text(kPerPosition)));
  const auto droppers = droppers_of(m);
  ASSERT_EQ(droppers.size(), 18u);
  int seen[2] = {0, 0};
  for (const BarElement* b : droppers) {
    ASSERT_GE(b->index_in_span, 0);
    ASSERT_LT(b->index_in_span, 9);
    const double EA = kPerPosition[b->index_in_span];
    const double x = 0.5 * (m.nodes[b->nodes[0]].position.x() + m.nodes[b->nodes[1]].position.x());
    EXPECT_NEAR(x - 60.0 * b->span, kDropperPositions[b->index_in_span], 1e-9);
    EXPECT_DOUBLE_EQ(b->axial_rigidity, EA);
    EXPECT_LT(rel(b->stiffness, EA / design_length(m, *b)), 1e-15);
    ++seen[b->span];
  }
  EXPECT_EQ(seen[0], 9);
  EXPECT_EQ(seen[1], 9);
}

TEST(DropperEA, StiffnessKeyUnchanged) {
  const CatenaryMesh m = build_text(design_with(kStiffnessLine));
  for (const BarElement* b : droppers_of(m)) {
    EXPECT_EQ(b->stiffness, 1.0e5);
    EXPECT_EQ(b->axial_rigidity, 0.0);
    EXPECT_EQ(bar_parameters(*b).stiffness, 1.0e5);
    EXPECT_EQ(bar_parameters(*b).axial_rigidity, 0.0);
  }
}

TEST(DropperEA, ParametersWithoutAFile) {
  ParametricDesign d = design_fixtures::reference_design(2);
  d.droppers.stiffness = 0;
  d.droppers.EA = 2.0e5;
  const CatenaryMesh m = build_parametric(d);
  for (const BarElement* b : droppers_of(m))
    EXPECT_LT(rel(b->stiffness, 2.0e5 / design_length(m, *b)), 1e-15);
  d.droppers.stiffness = 1.0e5;  // both
  const std::string msg = message_of([&] { build_parametric(d); });
  EXPECT_TRUE(contains(msg, "reference-parameters")) << msg;
  EXPECT_TRUE(contains(msg, "droppers.EA")) << msg;
  EXPECT_TRUE(contains(msg, "not both")) << msg;
  // Spans with their own positions: a list per position needs as many.
  d.droppers.stiffness = 0;
  d.droppers.EA.reset();
  d.droppers.EA_per_position = kPerPosition;
  d.droppers.spans = {{{2}, {10.0, 30.0, 50.0}, {}}};
  const std::string spans = message_of([&] { build_parametric(d); });
  EXPECT_TRUE(contains(spans, "key 'droppers.EA'")) << spans;
  EXPECT_TRUE(contains(spans, "droppers.spans[0] has 3 droppers")) << spans;
  d.droppers.spans = {{{2}, {5.0, 10.0, 15.0, 20.0, 30.0, 40.0, 45.0, 50.0, 55.0}, {}}};
  const CatenaryMesh own = build_parametric(d);
  for (const BarElement* b : droppers_of(own))
    EXPECT_DOUBLE_EQ(b->axial_rigidity, kPerPosition[b->index_in_span]);
}

// ------------------------------------------------------------ errors ----

TEST(DropperEA, Errors) {
  struct Case {
    const char* replacement;
    const char* key;
    const char* reason;
  };
  const Case cases[] = {
      {"stiffness: 1.0e5\n  EA: 1.0e5", "key 'droppers.EA'", "not both"},
      {"EA: -1.0e5", "key 'droppers.EA'", "must be positive"},
      {"EA: 0", "key 'droppers.EA'", "must be positive"},
      {"EA: 2.0e11", "key 'droppers.EA'", "at most"},
      {"EA: [1.0e5, 1.0e5, 1.0e5]", "key 'droppers.EA'",
       "needs one value per dropper position (9 in droppers.positions), got 3"},
      {"EA: [1.1e5, 1.2e5, 1.3e5, -1.4e5, 1.5e5, 1.6e5, 1.7e5, 1.8e5, 1.9e5]",
       "key 'droppers.EA[3]'", "must be positive"},
      {"EA: []", "key 'droppers.EA'", "must be a number or a list"},
      {"EA: stiff", "key 'droppers.EA'", ""},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.replacement);
    const std::string msg = message_of([&] { build_text(design_with(c.replacement)); });
    EXPECT_TRUE(contains(msg, "variant.yaml")) << msg;
    EXPECT_TRUE(contains(msg, c.key)) << msg;
    EXPECT_TRUE(contains(msg, c.reason)) << msg;
  }
  // Neither key.
  const std::string neither = message_of([&] { build_text(design_with("")); });
  EXPECT_TRUE(contains(neither, "variant.yaml")) << neither;
  EXPECT_TRUE(contains(neither, "key 'droppers.stiffness'")) << neither;
  EXPECT_TRUE(contains(neither, "required key is missing")) << neither;
  EXPECT_TRUE(contains(neither, "'EA' [N]")) << neither;
}

// ------------------------------------------------------- form-finding ----

// After form-finding every dropper's stiffness is EA / L0 with L0 its
// form-found unstressed length, and the bar force is EA (l - L0) / L0.
TEST(DropperEA, FormFoundLengthSetsTheStiffness) {
  const CatenaryMesh mesh = build_text(design_with(per_position_text(kPerPosition)));
  assembly::CatenarySystem system(PETSC_COMM_WORLD, mesh, assembly::form_finding_unknowns(mesh));
  Vec x = system.create_vector();
  system.design_state(x);
  const auto result = solvers::solve_static(system, x, true);
  VecDestroy(&x);
  ASSERT_TRUE(result.converged) << result.converged_reason;
  EXPECT_LE(result.max_height_error_m, 1e-4);
  EXPECT_LE(result.max_tension_error_rel, 1e-3);
  const CatenaryMesh& found = system.mesh();
  int checked = 0;
  double shortest = 1e9, longest = 0;
  for (std::size_t i = 0; i < found.bars.size(); ++i) {
    const BarElement& b = found.bars[i];
    if (b.kind != BarKind::dropper) continue;
    const double EA = kPerPosition[b.index_in_span];
    const double L0 = b.unstressed_length;
    // Form-finding moved L0 off the design length (the droppers carry the
    // contact wire's weight).
    EXPECT_GT(std::abs(L0 - design_length(found, b)), 1e-6);
    EXPECT_LT(rel(b.stiffness, EA / L0), 1e-15);
    EXPECT_LT(rel(bar_parameters(b).stiffness, EA / L0), 1e-15);
    const double N = result.bar_forces[i], l = result.bar_lengths[i];
    EXPECT_GT(N, 0.0);
    EXPECT_LT(std::abs(N - EA * (l - L0) / L0), 1e-9 * N);
    shortest = std::min(shortest, L0);
    longest = std::max(longest, L0);
    ++checked;
  }
  EXPECT_EQ(checked, 18);
  EXPECT_GT(longest / shortest, 1.5);
}
