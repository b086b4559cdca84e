#include "pcsim/core/triplet_pattern.hpp"

#include <algorithm>

namespace pcsim::core {

bool TripletPattern::same_positions(const std::vector<Eigen::Triplet<double>>& triplets,
                                    Eigen::Index n) const {
  if (pattern_.rows() != n || triplets.size() != positions_.size()) return false;
  for (std::size_t k = 0; k < triplets.size(); ++k)
    if (std::int64_t(triplets[k].row()) * n + triplets[k].col() != positions_[k]) return false;
  return true;
}

// setFromTriplets, then each triplet's slot found in its (sorted) column.
void TripletPattern::analyse(const std::vector<Eigen::Triplet<double>>& triplets, Eigen::Index n) {
  pattern_.resize(n, n);
  pattern_.setFromTriplets(triplets.begin(), triplets.end());
  pattern_.makeCompressed();
  const int* outer = pattern_.outerIndexPtr();
  const int* inner = pattern_.innerIndexPtr();
  positions_.resize(triplets.size());
  slots_.resize(triplets.size());
  first_.assign(triplets.size(), 0);
  std::vector<char> seen(pattern_.nonZeros(), 0);
  for (std::size_t k = 0; k < triplets.size(); ++k) {
    const auto& t = triplets[k];
    positions_[k] = std::int64_t(t.row()) * n + t.col();
    const int* slot = std::lower_bound(inner + outer[t.col()], inner + outer[t.col() + 1], t.row());
    slots_[k] = static_cast<int>(slot - inner);
    first_[k] = !seen[slots_[k]];
    seen[slots_[k]] = 1;
  }
  ++analyses_;
}

void TripletPattern::assemble(const std::vector<Eigen::Triplet<double>>& triplets, Eigen::Index n,
                              Eigen::SparseMatrix<double>& out) {
  if (!same_positions(triplets, n)) {
    analyse(triplets, n);
  } else {
    // setFromTriplets's sum of an entry's duplicates: the first, plus each
    // next in the triplets' order.
    double* values = pattern_.valuePtr();
    for (std::size_t k = 0; k < triplets.size(); ++k) {
      if (first_[k])
        values[slots_[k]] = triplets[k].value();
      else
        values[slots_[k]] += triplets[k].value();
    }
  }
  out = pattern_;
}

}  // namespace pcsim::core
