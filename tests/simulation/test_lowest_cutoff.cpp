// The cut-off a modal run takes when the pilot's last raise still leaves
// figures outside the targets (simulation::lowest_sufficient_cutoff): the
// lowest one tried whose every reduction error is within its target or no
// larger than at the highest. Figures: mean, σ, Fm+3σ, actual max, uplift,
// Fm−3σ, actual min, loss of contact (targets 0.5, 1, 1, 1, 2, 2, 2, 0.1).
#include <gtest/gtest.h>

#include <stdexcept>

#include "pcsim/simulation/accuracy_pilot.hpp"

namespace {

using pcsim::simulation::FigureErrors;
using pcsim::simulation::lowest_sufficient_cutoff;

FigureErrors errors(const char* pantograph, std::array<double, 8> value) {
  FigureErrors e;
  e.pantograph = pantograph;
  e.value = value;
  return e;
}

// A loss of contact that no raise changes (a flipped sample, 0.21 pt at
// every cut-off; runs/lines/irregular-random-300.yaml): the lowest cut-off
// whose other figures are within their targets serves as well as the last.
TEST(LowestSufficientCutoff, ARaiseThatChangesNothingOutsideIsNotTaken) {
  const std::vector<std::vector<FigureErrors>> tried = {
      {errors("p", {0.1, 1.4, 0.6, 0.8, 0.3, 0.9, 1.0, 0.21})},  // σ outside: not sufficient
      {errors("p", {0.1, 0.7, 0.3, 0.5, 0.3, 0.6, 0.9, 0.21})},
      {errors("p", {0.0, 0.4, 0.2, 0.3, 0.2, 0.4, 0.5, 0.21})},
      {errors("p", {0.0, 0.3, 0.1, 0.2, 0.2, 0.3, 0.4, 0.21})}};
  EXPECT_EQ(lowest_sufficient_cutoff(tried), 1u);
}

// A figure outside at the last cut-off that the raises brought closer (an
// actual maximum 1.30 → 1.07 %, the trailing pantograph of
// runs/interaction/three-pantographs-300.yaml): the last cut-off stays.
TEST(LowestSufficientCutoff, ARaiseThatBringsAFigureCloserIsKept) {
  const std::vector<std::vector<FigureErrors>> tried = {
      {errors("leading", {0, 0.2, 0.1, 0.2, 0.1, 0.2, 0.1, 0}),
       errors("trailing", {0, 0.8, 0.5, 1.30, 0.2, 1.1, 0.2, 0.76})},
      {errors("leading", {0, 0.2, 0.1, 0.2, 0.1, 0.2, 0.1, 0}),
       errors("trailing", {0, 0.7, 0.4, 1.07, 0.2, 1.1, 0.2, 0.76})}};
  EXPECT_EQ(lowest_sufficient_cutoff(tried), 1u);
}

// Figures that move back and forth with the cut-off (the pilot of
// runs/interaction/three-pantographs-300.yaml: the trailing pantograph's
// actual maximum 1.019, 1.080, 1.069 % and loss of contact 0.764, 0.625,
// 0.764 pt at 87.1, 108.8 and 136.1 Hz): 87.1 Hz is no worse than the last,
// but 108.8 Hz, above it, had the loss of contact closer, so the figures are
// not settled and the last cut-off stays.
TEST(LowestSufficientCutoff, FiguresNotSettledKeepTheLast) {
  const std::vector<std::vector<FigureErrors>> tried = {
      {errors("trailing", {0, 0.8, 0.4, 1.019, 0.2, 1.2, 0.8, 0.764})},
      {errors("trailing", {0, 0.7, 0.4, 1.080, 0.2, 1.1, 0.5, 0.625})},
      {errors("trailing", {0, 0.7, 0.4, 1.069, 0.2, 1.1, 0.5, 0.764})}};
  EXPECT_EQ(lowest_sufficient_cutoff(tried), 2u);
}

// Every pantograph counts: the leading one's σ outside at the lower
// cut-off keeps the higher one although the trailing one is alike at both.
TEST(LowestSufficientCutoff, EveryPantographCounts) {
  const std::vector<std::vector<FigureErrors>> tried = {
      {errors("leading", {0, 1.2, 0.1, 0.2, 0.1, 0.2, 0.1, 0}),
       errors("trailing", {0, 0.3, 0.1, 0.2, 0.1, 0.2, 0.1, 0.5})},
      {errors("leading", {0, 0.6, 0.1, 0.2, 0.1, 0.2, 0.1, 0}),
       errors("trailing", {0, 0.3, 0.1, 0.2, 0.1, 0.2, 0.1, 0.5})}};
  EXPECT_EQ(lowest_sufficient_cutoff(tried), 1u);
  // Equal at the boundary: no larger is sufficient.
  auto equal = tried;
  equal[0][0].value[1] = 1.0;
  EXPECT_EQ(lowest_sufficient_cutoff(equal), 0u);
}

TEST(LowestSufficientCutoff, OneCutoffIsItselfAndNoneIsAnError) {
  EXPECT_EQ(lowest_sufficient_cutoff({{errors("p", {0, 2, 0, 0, 0, 0, 0, 1})}}), 0u);
  EXPECT_THROW(lowest_sufficient_cutoff({}), std::invalid_argument);
}

}  // namespace
