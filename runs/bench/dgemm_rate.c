/* The rate of one dgemm shaped as the moving window's shift products
 * (src/simulation/modal_shift.cpp: C = A^T B, A and B 15790 x 256, the
 * 11-span window's local rows by a block of 256 vectors), through whatever
 * libblas.so.3 the dynamic linker finds. Prints GFlop/s (best of REPEAT).
 *   dgemm_rate [ROWS] [REPEAT]                   (runs/bench_blas.sh) */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

void dgemm_(const char*, const char*, const int*, const int*, const int*, const double*,
            const double*, const int*, const double*, const int*, const double*, double*,
            const int*);

static double seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char** argv) {
  const int k = argc > 1 ? atoi(argv[1]) : 15790, repeat = argc > 2 ? atoi(argv[2]) : 5;
  const int n = 256;
  double* a = malloc(sizeof(double) * (size_t)k * n);
  double* b = malloc(sizeof(double) * (size_t)k * n);
  double* c = malloc(sizeof(double) * (size_t)n * n);
  if (!a || !b || !c) return 1;
  for (size_t i = 0; i < (size_t)k * n; ++i) a[i] = b[i] = (double)(i % 1000) / 1000.0;
  const double one = 1, zero = 0;
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const double t0 = seconds();
    dgemm_("T", "N", &n, &n, &k, &one, a, &k, b, &k, &zero, c, &n);
    const double t = seconds() - t0;
    if (t < best) best = t;
  }
  printf("%.1f\n", 2.0 * n * n * k / best / 1e9);
  free(a);
  free(b);
  free(c);
  return 0;
}
