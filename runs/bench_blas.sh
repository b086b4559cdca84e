#!/usr/bin/env bash
# The BLAS behind pcsim's dense products (docs/benchmarks.md, "The BLAS
# behind the modes"): the rate of a dgemm shaped as the moving window's shift
# products (runs/bench/dgemm_rate.c) by Eigen's kernels, as pcsim computed
# them before (runs/bench/eigen_gemm_rate.cpp), and with each BLAS that Debian's
# libblas.so.3 alternatives offer on this machine (the reference BLAS, BLIS
# of scripts/setup-deps.sh, OpenBLAS if installed), and which one a plain run
# takes. Run it on an otherwise idle machine: it measures wall time.
#   runs/bench_blas.sh
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
gcc -O2 -o "$tmp/dgemm_rate" runs/bench/dgemm_rate.c -lblas
g++ -O2 -DNDEBUG -I/usr/include/eigen3 -o "$tmp/eigen_gemm_rate" runs/bench/eigen_gemm_rate.cpp
lib=/usr/lib/x86_64-linux-gnu
printf '%-44s %10s\n' "libblas.so.3" "GFlop/s"
printf '%-44s %10s\n' "(none: Eigen's kernels, pcsim's flags)" "$("$tmp/eigen_gemm_rate")"
for dir in "$lib/blas" "$lib/blis-serial" "$lib/openblas-serial" "$lib/openblas-pthread"; do
  [ -e "$dir/libblas.so.3" ] || continue
  printf '%-44s %10s\n' "$dir" "$(LD_LIBRARY_PATH=$dir "$tmp/dgemm_rate")"
done
echo "a plain run takes: $(readlink -f "$lib/libblas.so.3")"
