#pragma once
// A sparse matrix assembled again and again from triplets at the same
// positions (a model's step tangent at every Newton iteration): the first
// assembly is Eigen's setFromTriplets, which sorts them and sums duplicates;
// it keeps, for each triplet, the slot of its entry in the compressed matrix.
// While the triplets' positions are those of that assembly, later ones write
// the values straight into the kept pattern, each entry summed in the
// triplets' order as setFromTriplets sums it: the same bits, without the
// sort and the temporary matrix (docs/benchmarks.md, "The flexible DSA-380's
// tangent in a kept pattern").
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

namespace pcsim::core {

class TripletPattern {
 public:
  // out = the n x n matrix of the triplets (duplicates summed, explicit zeros
  // kept), as Eigen's setFromTriplets gives it.
  void assemble(const std::vector<Eigen::Triplet<double>>& triplets, Eigen::Index n,
                Eigen::SparseMatrix<double>& out);
  // How many assemblies sorted the triplets (a new or changed pattern).
  long analyses() const { return analyses_; }

 private:
  bool same_positions(const std::vector<Eigen::Triplet<double>>& triplets, Eigen::Index n) const;
  void analyse(const std::vector<Eigen::Triplet<double>>& triplets, Eigen::Index n);

  Eigen::SparseMatrix<double> pattern_;
  std::vector<std::int64_t> positions_;  // row * n + col of each triplet analysed
  std::vector<int> slots_;               // its entry in pattern_'s values
  std::vector<char> first_;              // the first triplet of its entry
  long analyses_ = 0;
};

}  // namespace pcsim::core
