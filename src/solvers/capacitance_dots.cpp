#include "capacitance_dots.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "pcsim/core/error.hpp"
#include "pcsim/core/vector_units.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define PCSIM_X86_KERNEL 1
#endif

namespace pcsim::solvers {

namespace {

constexpr PetscInt kBlock = 256;  // 2 kB a vector: every stream of a block stays in L1
constexpr int kLanes = 4;

// lanes[4 p + l] += a[j] b[p][j] over j in [begin, end) with j - begin = l
// (mod 4): begin is a multiple of 4, so a lane holds the same j's whatever
// the blocks.
void portable_dots(const double* a, const double* const* b, std::size_t count, PetscInt begin,
                   PetscInt end, double* lanes) {
  for (std::size_t p = 0; p < count; ++p)
    for (PetscInt j = begin; j < end; ++j)
      lanes[kLanes * p + (j - begin) % kLanes] += a[j] * b[p][j];
}

#ifdef PCSIM_X86_KERNEL
// Four vectors b at a time share each load of a (fused multiply-adds in four
// independent chains); the tail as the portable kernel's lanes.
__attribute__((target("avx2,fma"))) void vector_dots(const double* a, const double* const* b,
                                                     std::size_t count, PetscInt begin,
                                                     PetscInt end, double* lanes) {
  const PetscInt body = begin + (end - begin) / kLanes * kLanes;
  std::size_t p = 0;
  for (; p + 4 <= count; p += 4) {
    double* l = lanes + kLanes * p;
    __m256d s0 = _mm256_loadu_pd(l), s1 = _mm256_loadu_pd(l + 4);
    __m256d s2 = _mm256_loadu_pd(l + 8), s3 = _mm256_loadu_pd(l + 12);
    for (PetscInt j = begin; j < body; j += kLanes) {
      const __m256d av = _mm256_loadu_pd(a + j);
      s0 = _mm256_fmadd_pd(av, _mm256_loadu_pd(b[p] + j), s0);
      s1 = _mm256_fmadd_pd(av, _mm256_loadu_pd(b[p + 1] + j), s1);
      s2 = _mm256_fmadd_pd(av, _mm256_loadu_pd(b[p + 2] + j), s2);
      s3 = _mm256_fmadd_pd(av, _mm256_loadu_pd(b[p + 3] + j), s3);
    }
    _mm256_storeu_pd(l, s0);
    _mm256_storeu_pd(l + 4, s1);
    _mm256_storeu_pd(l + 8, s2);
    _mm256_storeu_pd(l + 12, s3);
  }
  for (; p < count; ++p) {
    double* l = lanes + kLanes * p;
    __m256d s0 = _mm256_loadu_pd(l);
    for (PetscInt j = begin; j < body; j += kLanes)
      s0 = _mm256_fmadd_pd(_mm256_loadu_pd(a + j), _mm256_loadu_pd(b[p] + j), s0);
    _mm256_storeu_pd(l, s0);
  }
  for (p = 0; p < count; ++p)
    for (PetscInt j = body; j < end; ++j)
      lanes[kLanes * p + (j - begin) % kLanes] =
          std::fma(a[j], b[p][j], lanes[kLanes * p + (j - begin) % kLanes]);
}
#endif

using DotKernel = void (*)(const double*, const double* const*, std::size_t, PetscInt, PetscInt,
                           double*);

DotKernel chosen_kernel() {
#ifdef PCSIM_X86_KERNEL
  return vector_units().avx2_fma ? vector_dots : portable_dots;
#else
  return portable_dots;
#endif
}

std::vector<const PetscScalar*> read_all(const std::vector<Vec>& vs) {
  std::vector<const PetscScalar*> a(vs.size());
  for (std::size_t j = 0; j < vs.size(); ++j) PCSIM_PETSC(VecGetArrayRead(vs[j], &a[j]));
  return a;
}

void release_all(const std::vector<Vec>& vs, std::vector<const PetscScalar*>& a) {
  for (std::size_t j = 0; j < vs.size(); ++j) PCSIM_PETSC(VecRestoreArrayRead(vs[j], &a[j]));
}

// The lanes of each product added in a tree of two levels.
void sum_lanes(const std::vector<double>& lanes, std::vector<double>& out) {
  for (std::size_t p = 0; p < out.size(); ++p) {
    const double* l = &lanes[kLanes * p];
    out[p] = (l[0] + l[2]) + (l[1] + l[3]);
  }
}

// sum_p w[p] v[index[p] - lo] over the entries of the rank's rows [lo, lo + n).
double sparse_dot(const SparseU& u, const double* v, PetscInt lo, PetscInt n) {
  double sum = 0;
  for (std::size_t p = 0; p < u.size; ++p) {
    const PetscInt i = u.index[p] - lo;
    if (i >= 0 && i < n) sum += u.weight[p] * v[i];
  }
  return sum;
}

// The rank's part of every product from the u's entries; a symmetric row as
// the dense kernel's (u_a . z_b with a <= b, the other rows' entries 0).
void sparse_local_dots(const CapacitanceDots& in, std::vector<double>& uz, std::vector<double>& zu,
                       std::vector<double>& ux) {
  const std::size_t k = in.us.size();
  const auto& u = in.sparse_us;
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(in.zs[0], &lo, &hi));
  const PetscInt n = hi - lo;
  auto z = read_all(in.zs);
  std::vector<bool> is_row(k, false);
  for (std::size_t i : in.rows) is_row[i] = true;
  for (std::size_t r = 0; r < in.rows.size(); ++r) {
    const std::size_t i = in.rows[r];
    for (std::size_t j = 0; j < k; ++j) {
      if (in.symmetric) {
        if (j >= i) uz[r * k + j] = sparse_dot(u[i], z[j], lo, n);
        if (j < i && !is_row[j]) uz[r * k + j] = sparse_dot(u[j], z[i], lo, n);
        continue;
      }
      uz[r * k + j] = sparse_dot(u[i], z[j], lo, n);
      if (in.transposed) zu[r * k + j] = sparse_dot(u[j], z[i], lo, n);
    }
  }
  release_all(in.zs, z);
  if (!in.x) return;
  const PetscScalar* x;
  PCSIM_PETSC(VecGetArrayRead(in.x, &x));
  for (std::size_t j = 0; j < k; ++j) ux[j] = sparse_dot(u[j], x, lo, n);
  PCSIM_PETSC(VecRestoreArrayRead(in.x, &x));
}

// The dense kernel's pass over the rank's entries (4 lanes, blocks of 256).
void dense_local_dots(const CapacitanceDots& in, std::vector<double>& uz, std::vector<double>& zu,
                      std::vector<double>& ux, bool vector_kernel) {
  const std::size_t k = in.us.size(), nr = in.rows.size();
  PetscInt n = 0;
  PCSIM_PETSC(VecGetLocalSize(in.us[0], &n));
  auto u = read_all(in.us), z = read_all(in.zs);
  const PetscScalar* x = nullptr;
  if (in.x) PCSIM_PETSC(VecGetArrayRead(in.x, &x));
  const DotKernel kernel = vector_kernel ? chosen_kernel() : portable_dots;
  // A symmetric row's products below its term with the terms that are no
  // rows, as z_i . u_j (the same bits as u_j . z_i: each lane's products
  // and sums are those of row j's).
  std::vector<std::vector<const double*>> lower(in.symmetric ? nr : 0);
  std::vector<std::vector<std::size_t>> lower_terms(lower.size());
  std::vector<std::vector<double>> lower_lanes(lower.size());
  if (in.symmetric) {
    std::vector<bool> is_row(k, false);
    for (std::size_t i : in.rows) is_row[i] = true;
    for (std::size_t r = 0; r < nr; ++r) {
      for (std::size_t j = 0; j < in.rows[r]; ++j)
        if (!is_row[j]) {
          lower[r].push_back(u[j]);
          lower_terms[r].push_back(j);
        }
      lower_lanes[r].assign(kLanes * lower[r].size(), 0.0);
    }
  }
  // u_r . z_j as row r of uz; u_j . z_r as row r of zu (u_j first: the bits
  // of row j formed whole); x . u_j.
  std::vector<double> uz_lanes(kLanes * uz.size(), 0.0), zu_lanes(kLanes * zu.size(), 0.0);
  std::vector<double> ux_lanes(kLanes * ux.size(), 0.0);
  for (PetscInt b = 0; b < n; b += kBlock) {
    const PetscInt end = std::min(b + kBlock, n);
    for (std::size_t r = 0; r < nr; ++r) {
      const std::size_t i = in.rows[r];
      if (in.symmetric) {
        kernel(u[i], z.data() + i, k - i, b, end, &uz_lanes[kLanes * (r * k + i)]);
        if (!lower[r].empty())
          kernel(z[i], lower[r].data(), lower[r].size(), b, end, lower_lanes[r].data());
        continue;
      }
      kernel(u[i], z.data(), k, b, end, &uz_lanes[kLanes * r * k]);
      if (!in.transposed) continue;
      for (std::size_t j = 0; j < k; ++j)
        kernel(u[j], &z[i], 1, b, end, &zu_lanes[kLanes * (r * k + j)]);
    }
    if (x) kernel(x, u.data(), k, b, end, ux_lanes.data());
  }
  if (x) PCSIM_PETSC(VecRestoreArrayRead(in.x, &x));
  release_all(in.zs, z);
  release_all(in.us, u);
  sum_lanes(uz_lanes, uz);
  sum_lanes(zu_lanes, zu);
  sum_lanes(ux_lanes, ux);
  for (std::size_t r = 0; r < lower.size(); ++r) {
    std::vector<double> sums(lower_terms[r].size());
    sum_lanes(lower_lanes[r], sums);
    for (std::size_t p = 0; p < sums.size(); ++p) uz[r * k + lower_terms[r][p]] = sums[p];
  }
}

}  // namespace

void capacitance_dots(const CapacitanceDots& in, std::vector<double>& uz, std::vector<double>& zu,
                      std::vector<double>& ux, bool vector_kernel) {
  const std::size_t k = in.us.size(), nr = in.rows.size();
  uz.assign(nr * k, 0.0);
  zu.assign(in.transposed ? nr * k : 0, 0.0);
  ux.assign(in.x ? k : 0, 0.0);
  if (k == 0) return;
  if (in.sparse_us.size() == k)
    sparse_local_dots(in, uz, zu, ux);
  else
    dense_local_dots(in, uz, zu, ux, vector_kernel);
  int size = 1;
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(in.us[0]));
  MPI_Comm_size(comm, &size);
  if (size == 1) return;
  std::vector<double> all(uz);
  all.insert(all.end(), zu.begin(), zu.end());
  all.insert(all.end(), ux.begin(), ux.end());
  MPI_Allreduce(MPI_IN_PLACE, all.data(), static_cast<int>(all.size()), MPI_DOUBLE, MPI_SUM, comm);
  std::copy(all.begin(), all.begin() + uz.size(), uz.begin());
  std::copy(all.begin() + uz.size(), all.begin() + uz.size() + zu.size(), zu.begin());
  std::copy(all.end() - ux.size(), all.end(), ux.begin());
}

}  // namespace pcsim::solvers
