// The cut-off a modal run takes when the pilot's last raise still leaves
// figures outside the targets (simulation::lowest_sufficient_cutoff): the
// lowest one tried whose every reduction error is within its target or no
// larger than at the highest. Figures: mean, σ, Fm+3σ, actual max, uplift,
// Fm−3σ, actual min, loss of contact (targets 0.5, 1, 1, 1, 2, 2, 2, 0.1).
// And whether the pilot raises beyond its third raise
// (simulation::last_raise_closer): every figure outside came closer.
#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <utility>
#include <vector>

#include "pcsim/simulation/accuracy_pilot.hpp"

namespace {

using pcsim::simulation::FigureErrors;
using pcsim::simulation::last_raise_closer;
using pcsim::simulation::lowest_sufficient_cutoff;

FigureErrors errors(const char* pantograph, std::array<double, 8> value) {
  FigureErrors e;
  e.pantograph = pantograph;
  e.value = value;
  return e;
}

// A loss of contact that the last raise does not change (the pilot of
// runs/lines/irregular-random-300.yaml: 0.972, 0.625, 0.208 and 0.208 pt at
// 69.7, 87.1, 108.8 and 136.1 Hz, σ 2.300 and 1.198 % at the first two):
// 108.8 Hz serves as well as the last.
TEST(LowestSufficientCutoff, ARaiseThatChangesNothingOutsideIsNotTaken) {
  const std::vector<std::vector<FigureErrors>> tried = {
      {errors("p", {0.1, 2.300, 1.094, 0.8, 0.3, 0.9, 2.806, 0.972})},
      {errors("p", {0.1, 1.198, 0.6, 0.5, 0.3, 0.6, 0.9, 0.625})},
      {errors("p", {0.0, 0.5, 0.2, 0.3, 0.2, 0.4, 0.5, 0.208})},
      {errors("p", {0.0, 0.4, 0.1, 0.2, 0.2, 0.3, 0.4, 0.208})}};
  EXPECT_EQ(lowest_sufficient_cutoff(tried), 2u);
}

// Two pantographs; each case a cut-off's row of leading and trailing errors.
using Row = std::array<double, 8>;
struct TwoPantographCase {
  const char* why;
  std::vector<std::pair<Row, Row>> tried;  // leading, trailing; ascending cut-offs
  std::size_t expected;
};

TEST(LowestSufficientCutoff, TwoPantographs) {
  const Row quiet = {0, 0.2, 0.1, 0.2, 0.1, 0.2, 0.1, 0};
  const std::vector<TwoPantographCase> cases = {
      // A figure outside at the last cut-off that the raise brought closer
      // (the trailing pantograph's actual maximum 1.30 → 1.07 %): the last
      // stays.
      {"closer",
       {{quiet, {0, 0.8, 0.5, 1.30, 0.2, 1.1, 0.2, 0.76}},
        {quiet, {0, 0.7, 0.4, 1.07, 0.2, 1.1, 0.2, 0.76}}},
       1},
      // Every pantograph counts: the leading one's σ outside at the lower
      // cut-off keeps the higher one although the trailing one is alike.
      {"leading",
       {{{0, 1.2, 0.1, 0.2, 0.1, 0.2, 0.1, 0}, {0, 0.3, 0.1, 0.2, 0.1, 0.2, 0.1, 0.5}},
        {{0, 0.6, 0.1, 0.2, 0.1, 0.2, 0.1, 0}, {0, 0.3, 0.1, 0.2, 0.1, 0.2, 0.1, 0.5}}},
       1},
      // Equal to the target at the lower cut-off: no larger is sufficient.
      {"at target",
       {{{0, 1.0, 0.1, 0.2, 0.1, 0.2, 0.1, 0}, {0, 0.3, 0.1, 0.2, 0.1, 0.2, 0.1, 0.5}},
        {{0, 0.6, 0.1, 0.2, 0.1, 0.2, 0.1, 0}, {0, 0.3, 0.1, 0.2, 0.1, 0.2, 0.1, 0.5}}},
       0}};
  for (const auto& c : cases) {
    std::vector<std::vector<FigureErrors>> tried;
    for (const auto& row : c.tried)
      tried.push_back({errors("leading", row.first), errors("trailing", row.second)});
    EXPECT_EQ(lowest_sufficient_cutoff(tried), c.expected) << c.why;
  }
}

// Figures that move back and forth with the cut-off (the pilot of
// runs/interaction/three-pantographs-300.yaml: the trailing pantograph's
// actual maximum 1.019, 1.080, 1.069 % and loss of contact 0.764, 0.625,
// 0.764 pt at 87.1, 108.8 and 136.1 Hz): 87.1 Hz is no worse than the last,
// but 108.8 Hz, above it, had the loss of contact closer, so the figures are
// not settled and the last cut-off stays.
TEST(LowestSufficientCutoff, FiguresNotSettledKeepTheLast) {
  std::vector<std::vector<FigureErrors>> tried;
  for (const auto& row : {std::array<double, 8>{0, 0.8, 0.4, 1.019, 0.2, 1.2, 0.8, 0.764},
                          std::array<double, 8>{0, 0.7, 0.4, 1.080, 0.2, 1.1, 0.5, 0.625},
                          std::array<double, 8>{0, 0.7, 0.4, 1.069, 0.2, 1.1, 0.5, 0.764}})
    tried.push_back({errors("trailing", row)});
  EXPECT_EQ(lowest_sufficient_cutoff(tried), 2u);
}

TEST(LowestSufficientCutoff, OneCutoffIsItselfAndNoneIsAnError) {
  EXPECT_EQ(lowest_sufficient_cutoff({{errors("p", {0, 2, 0, 0, 0, 0, 0, 1})}}), 0u);
  EXPECT_THROW(lowest_sufficient_cutoff({}), std::invalid_argument);
}

// Beyond its third raise the pilot raises again only while the last raise
// brought every figure outside its target closer (last_raise_closer).
std::vector<std::vector<FigureErrors>> one_pantograph(std::vector<std::array<double, 8>> rows) {
  std::vector<std::vector<FigureErrors>> tried;
  for (const auto& row : rows) tried.push_back({errors("p", row)});
  return tried;
}

// A leading and a trailing pantograph at two cut-offs: the leading σ 1.4 then
// 1.2 % (outside, closer), the trailing loss of contact given.
std::vector<std::vector<FigureErrors>> two_pantographs(double trailing_loss_before,
                                                       double trailing_loss_last) {
  const auto leading = [](double sigma) {
    return errors("leading", {0, sigma, 0.1, 0.2, 0.1, 0.2, 0.1, 0});
  };
  const auto trailing = [](double loss) {
    return errors("trailing", {0, 0.2, 0.1, 0.2, 0.1, 0.2, 0.1, loss});
  };
  return {{leading(1.4), trailing(trailing_loss_before)},
          {leading(1.2), trailing(trailing_loss_last)}};
}

TEST(LastRaiseCloser, EveryFigureOutsideCloserRaisesAgain) {
  // The pilot of runs/lines/supports-300.yaml: loss of contact 0.139 and
  // 0.104 pt at 108.8 and 136.1 Hz, its only figure outside.
  EXPECT_TRUE(last_raise_closer(one_pantograph(
      {{0, 0.4, 0.2, 0.3, 0.1, 0.4, 0.2, 0.139}, {0, 0.3, 0.2, 0.2, 0.1, 0.3, 0.2, 0.104}})));
  // Two pantographs, each with a figure outside that came closer.
  EXPECT_TRUE(last_raise_closer(two_pantographs(0.3, 0.2)));
}

TEST(LastRaiseCloser, AFigureOutsideNotCloserEndsTheRaises) {
  // runs/lines/irregular-random-300.yaml: the loss of contact the same,
  // 0.208 pt at 108.8 and 136.1 Hz.
  EXPECT_FALSE(last_raise_closer(one_pantograph(
      {{0, 0.5, 0.2, 0.3, 0.2, 0.4, 0.5, 0.208}, {0, 0.4, 0.1, 0.2, 0.2, 0.3, 0.4, 0.208}})));
  // runs/interaction/three-pantographs-300.yaml's trailing pantograph: its
  // actual maximum closer (1.080 → 1.069 %), its loss of contact further
  // (0.625 → 0.764 pt).
  EXPECT_FALSE(last_raise_closer(one_pantograph(
      {{0, 0.7, 0.4, 1.080, 0.2, 1.1, 0.5, 0.625}, {0, 0.7, 0.4, 1.069, 0.2, 1.1, 0.5, 0.764}})));
  // A figure that went from within its target to outside it.
  EXPECT_FALSE(last_raise_closer(two_pantographs(0.0, 0.2)));
  // Nothing outside at the last cut-off, or a single cut-off: nothing to raise for.
  EXPECT_FALSE(last_raise_closer(one_pantograph(
      {{0, 1.5, 0.2, 0.3, 0.2, 0.4, 0.5, 0.2}, {0, 0.5, 0.2, 0.3, 0.2, 0.4, 0.5, 0.1}})));
  EXPECT_FALSE(last_raise_closer(one_pantograph({{0, 1.5, 0, 0, 0, 0, 0, 0.2}})));
}

}  // namespace
