// The domain decomposition's interior correction X = A_II^-1 A_IG
// (schur_dd.cpp) is computed dense, but a step matrix's inverse decays along
// the wires (within about a span of the cut, its mass term M / (beta dt^2)
// outweighing the stiffness), so on long parts most of its entries are
// negligible: 4 % are kept at 40 spans on 2 ranks, 42 % at 4 spans on 2
// (docs/scaling.md).
#pragma once

#include <petscmat.h>

namespace pcsim::solvers {

// X without its entries of magnitude at most 1e-18 times their column's
// largest: the product with a vector then moves by less than 1e-18 of its
// largest term, a hundred times below the rounding of the dense product
// (unit roundoff 1.1e-16). *X becomes a sparse copy (MATSEQAIJ) when at most
// half of its entries are kept (a stored sparse entry takes 12 bytes, a dense
// one 8), else stays as it is. *entries: X's entries, *stored: those it keeps.
void drop_negligible(Mat* X, double* entries, double* stored);

}  // namespace pcsim::solvers
