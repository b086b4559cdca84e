// What a process keeps between runs (simulation/setup_memory.hpp): the
// modal bases are bounded (kKeptBases, the oldest dropped first), found only
// under their key and from the cache file they came from, and shared, not
// copied (immutable: a run's model holds the kept one's memory). The runs
// that take them are in tests/simulation/test_two_runs.sh.
#include <gtest/gtest.h>

#include "pcsim/simulation/setup_memory.hpp"

namespace {

using namespace pcsim;

simulation::SharedBasis basis_of_size(int n) {
  catenary::ReducedBasis b;
  b.omega2.assign(n, 1.0);
  b.row_keys = {2};
  b.rows.assign(n, 0.5);
  return std::make_shared<const catenary::ReducedBasis>(std::move(b));
}

TEST(SetupMemory, BasesAreBoundedKeyedAndShared) {
  catenary::ModalSettings s;
  s.max_frequency_hz = 70;
  const std::string a = simulation::kept_basis_key("design-a", s);
  s.max_frequency_hz = 80;
  const std::string a80 = simulation::kept_basis_key("design-a", s);
  EXPECT_NE(a, a80);  // the cut-off is part of the key
  s.dropper_shapes = false;
  EXPECT_NE(a80, simulation::kept_basis_key("design-a", s));  // and the assembly's settings

  const auto made = basis_of_size(3);
  simulation::keep_basis(a, "a.h5@1", made);
  auto found = simulation::find_kept_basis(a, "a.h5@1");
  ASSERT_TRUE(found);
  EXPECT_EQ(found->size(), 3u);
  EXPECT_EQ(found.get(), made.get());  // the same memory, not a copy
  EXPECT_EQ(simulation::find_kept_basis(a, "a.h5@1").get(), made.get());
  // Another file (renamed over, or another cut-off's) or no file: not this basis.
  EXPECT_FALSE(simulation::find_kept_basis(a, "a.h5@2"));
  EXPECT_FALSE(simulation::find_kept_basis(a, ""));
  EXPECT_FALSE(simulation::find_kept_basis(a80, "a.h5@1"));

  simulation::keep_basis(a80, "a80.h5@1", basis_of_size(4));
  simulation::keep_basis("design-b", "b.h5@1", basis_of_size(5));
  EXPECT_EQ(simulation::kept_bases(), simulation::kKeptBases);
  EXPECT_FALSE(simulation::find_kept_basis(a, "a.h5@1"));  // the oldest, dropped
  EXPECT_EQ(found->rows[0], 0.5);  // a holder's basis outlives its being dropped
  EXPECT_TRUE(simulation::find_kept_basis(a80, "a80.h5@1"));
  EXPECT_TRUE(simulation::find_kept_basis("design-b", "b.h5@1"));
  // Kept again under the same key: replaced, not a second entry.
  simulation::keep_basis("design-b", "b.h5@2", basis_of_size(6));
  EXPECT_EQ(simulation::kept_bases(), 2u);
  EXPECT_EQ(simulation::find_kept_basis("design-b", "b.h5@2")->size(), 6u);
  EXPECT_FALSE(simulation::find_kept_basis("design-b", "b.h5@1"));
}

}  // namespace
