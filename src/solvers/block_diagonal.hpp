// The inverse of a matrix whose pattern is block diagonal with small blocks,
// block by block (the cheap path's J0 of the reduced-order catenary: its modes
// and each pantograph's block). A solve is one pass over the unknowns, where
// an LU factor's triangular pair with its permutations costs several
// (measured: 2 solves per step were ~8 % of a step of EN 50318, see
// docs/fidelity.md). Private to src/solvers (the low-rank step solver).
#pragma once

#include <petscmat.h>

#include <Eigen/Dense>
#include <utility>
#include <vector>

namespace pcsim::solvers {

class BlockDiagonalInverse {
 public:
  // Global rows [first, first + size) of a block solved elsewhere (the cheap
  // path's varying blocks: their rows of every solve are replaced).
  using Range = std::pair<PetscInt, PetscInt>;
  // The blocks of P's pattern on this rank: true if it is block diagonal with
  // blocks of at most max_block rows, each within this rank's rows and holding
  // its diagonal (collective: the same answer on every rank). A block that is
  // one of 'skipped' (this rank's) may be of any size: it is not factored.
  bool analyse(Mat P, PetscInt max_block = 32, const std::vector<Range>& skipped = {});
  // Inverts the blocks of P's current values; throws SolverError on a
  // singular one.
  void factor(Mat P);
  // x = P^-1 r (local to each rank); 0 in the rows of the skipped blocks.
  void solve(Vec r, Vec x) const;

 private:
  struct Block {
    PetscInt first = 0;  // local row
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  };
  std::vector<PetscInt> sizes_;      // each block's rows, negative for a skipped one
  Eigen::ArrayXd inverse_diagonal_;  // 1/d on the rows of 1 x 1 blocks, 0 elsewhere
  std::vector<Block> blocks_;        // the larger blocks
};

// P equals its transpose bit for bit (an AIJ matrix; any other type counts
// as unsymmetric): then u_i . P^-1 u_j = u_j . P^-1 u_i, and the capacitance
// may form each pair once (capacitance_dots.hpp, 'symmetric'). Collective.
bool exactly_symmetric(Mat P);

}  // namespace pcsim::solvers
