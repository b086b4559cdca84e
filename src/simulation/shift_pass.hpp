// A modal window's shift pass (moving_window.cpp): the state, rates and
// accelerations times the shift P (catenary::ReducedBasis::shift), stored
// in single precision, multiplied in double. The pass is bound by memory:
// float entries halve the bytes it reads (112 MB instead of 224 MB at 5286
// vectors), and P's rounding, 2^-24 of each entry, is far below what the
// projection on a truncated basis loses already.
#pragma once

namespace pcsim::simulation {

// y[s][i] = sum_k P(i, k) x[s][k] for s = 0, 1, 2 and rows i in [first,
// last) of the row-major m x m P. Each row's products are fused
// multiply-adds in double in 8 lanes (k mod 8), summed in a tree of 3 and
// then the tail: the vector kernel (AVX2 and FMA, where the processor has
// them) and the portable one give the same bits.
void shift_rows(const float* P, long m, const double* const x[3], double* const y[3], long first,
                long last);
// The same with the portable kernel (tests).
void shift_rows_portable(const float* P, long m, const double* const x[3], double* const y[3],
                         long first, long last);

}  // namespace pcsim::simulation
