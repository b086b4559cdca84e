#include "pcsim/simulation/modal_basis.hpp"

#include <malloc.h>
#include <petsctime.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>

#include "modal_basis_internal.hpp"
#include "mode_row_store.hpp"
#include "pcsim/assembly/wind_terms.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/spectrum.hpp"

namespace pcsim::simulation {

using catenary::basis_row_key;
using catenary::ModalData;
using namespace modal_detail;

namespace {

// Vectors per BLAS product over the dropper shapes' mass products: each such
// product reads the shapes once for the block instead of once per vector
// (docs/benchmarks.md, "The shapes' mass products in blocks").
constexpr long kProductBlock = 32;

// The local part of v into out.
void copy_local(Vec v, double* out) {
  PetscInt n;
  const PetscScalar* a;
  PCSIM_PETSC(VecGetLocalSize(v, &n));
  PCSIM_PETSC(VecGetArrayRead(v, &a));
  std::copy(a, a + n, out);
  PCSIM_PETSC(VecRestoreArrayRead(v, &a));
}

// Row index of a key in the sorted keys (the key must be there).
std::size_t row_of(const std::vector<long>& keys, long key) {
  const auto it = std::lower_bound(keys.begin(), keys.end(), key);
  if (it == keys.end() || *it != key) throw SolverError("reduced basis: a needed row is missing");
  return static_cast<std::size_t>(it - keys.begin());
}

// Solves with K_T (one Cholesky factorisation on every rank,
// solvers::use_line_cholesky_on_every_rank).
class StiffnessSolver {
 public:
  explicit StiffnessSolver(Mat K) {
    PC pc;
    PCSIM_PETSC(KSPCreate(PetscObjectComm(reinterpret_cast<PetscObject>(K)), &ksp_));
    PCSIM_PETSC(KSPSetOptionsPrefix(ksp_, "modal_static_"));
    PCSIM_PETSC(KSPSetOperators(ksp_, K, K));
    PCSIM_PETSC(KSPSetType(ksp_, KSPPREONLY));
    PCSIM_PETSC(KSPGetPC(ksp_, &pc));
    solvers::use_line_cholesky_on_every_rank(pc);
    PCSIM_PETSC(KSPSetFromOptions(ksp_));
    PCSIM_PETSC(KSPSetUp(ksp_));
  }
  ~StiffnessSolver() { KSPDestroy(&ksp_); }
  StiffnessSolver(const StiffnessSolver&) = delete;
  StiffnessSolver& operator=(const StiffnessSolver&) = delete;
  void solve(Vec b, Vec y) const { PCSIM_PETSC(KSPSolve(ksp_, b, y)); }

 private:
  KSP ksp_ = nullptr;
};

// The droppers' static shapes psi_d = K^-1 b_d, b_d = [-e; e] on the ends'
// positions (e: the bar's direction at the static configuration), their M
// products and rows.
class DropperShapes {
 public:
  DropperShapes(const assembly::CatenarySystem& system, Vec x, const Operators& op,
                const StiffnessSolver& K, const RowGather& rows, const std::vector<long>& keys);
  ~DropperShapes() {
    if (psi_) VecDestroyVecs(static_cast<PetscInt>(count_), &psi_);
  }
  DropperShapes(const DropperShapes&) = delete;
  DropperShapes& operator=(const DropperShapes&) = delete;
  std::size_t count() const { return count_; }
  Vec vector(std::size_t d) const { return psi_[d]; }
  // phi_k^T M psi_d for every d (out: count x shapes, column-major) of the
  // local parts of 'count' vectors side by side (phis: local x count);
  // collective.
  void mass_products(const double* phis, long count, double* out) const;
  const Eigen::MatrixXd& rows() const { return rows_; }
  const Eigen::MatrixXd& psi_M_psi() const { return psi_M_psi_; }
  const Eigen::MatrixXd& flexibility() const { return flexibility_; }

 private:
  std::size_t count_ = 0;
  MPI_Comm comm_ = MPI_COMM_NULL;
  Vec* psi_ = nullptr;
  Eigen::MatrixXd Mpsi_;         // local rows of M psi (local x count), one BLAS product
  Eigen::MatrixXd rows_;         // rows of psi (n_rows x count)
  Eigen::MatrixXd psi_M_psi_;    // psi^T M psi
  Eigen::MatrixXd flexibility_;  // b^T psi = b^T K^-1 b
};

DropperShapes::DropperShapes(const assembly::CatenarySystem& system, Vec x, const Operators& op,
                             const StiffnessSolver& K, const RowGather& rows,
                             const std::vector<long>& keys) {
  const auto& mesh = system.mesh();
  const auto& L = system.layout();
  const std::vector<double> values = system.all_node_values(x);
  std::vector<int> bars;
  for (std::size_t b = 0; b < mesh.bars.size(); ++b)
    if (mesh.bars[b].slack != catenary::SlackCriterion::none) bars.push_back(static_cast<int>(b));
  count_ = bars.size();
  if (count_ == 0) return;
  comm_ = PetscObjectComm(reinterpret_cast<PetscObject>(x));
  PCSIM_PETSC(VecDuplicateVecs(x, static_cast<PetscInt>(count_), &psi_));
  PetscInt local;
  PCSIM_PETSC(VecGetLocalSize(x, &local));
  Mpsi_.resize(local, static_cast<long>(count_));
  Vec b, Mpsi;
  PCSIM_PETSC(VecDuplicate(x, &b));
  PCSIM_PETSC(VecDuplicate(x, &Mpsi));
  rows_.resize(static_cast<long>(rows.size()), static_cast<long>(count_));
  std::vector<Eigen::Vector3d> direction(count_);
  for (std::size_t d = 0; d < count_; ++d) {
    const auto& nodes = mesh.bars[bars[d]].nodes;
    Eigen::Vector3d e;
    for (int c = 0; c < 3; ++c) e[c] = values[6 * nodes[1] + c] - values[6 * nodes[0] + c];
    direction[d] = e.normalized();
    PCSIM_PETSC(VecSet(b, 0.0));
    if (L.rank() == 0)
      for (int end = 0; end < 2; ++end)
        for (int c = 0; c < 3; ++c) {
          const PetscInt g = L.global_dof(nodes[end], c);
          if (g >= 0) PCSIM_PETSC(VecSetValue(b, g, (end ? 1 : -1) * direction[d][c], ADD_VALUES));
        }
    PCSIM_PETSC(VecAssemblyBegin(b));
    PCSIM_PETSC(VecAssemblyEnd(b));
    K.solve(b, psi_[d]);
    PCSIM_PETSC(MatMult(op.M, psi_[d], Mpsi));
    copy_local(Mpsi, Mpsi_.col(static_cast<long>(d)).data());
    rows.gather(psi_[d], rows_.col(static_cast<long>(d)).data());
  }
  PCSIM_PETSC(VecDestroy(&b));
  PCSIM_PETSC(VecDestroy(&Mpsi));
  const long n = static_cast<long>(count_);
  psi_M_psi_.resize(n, n);
  Eigen::MatrixXd block(local, std::min(n, kProductBlock));
  for (long first = 0; first < n; first += kProductBlock) {  // psi^T M psi, a block of rows
    const long width = std::min(kProductBlock, n - first);
    for (long j = 0; j < width; ++j) copy_local(psi_[first + j], block.col(j).data());
    product_tn(width, n, local, block.data(), Mpsi_.data(), psi_M_psi_.data() + first, n);
  }
  MPI_Allreduce(MPI_IN_PLACE, psi_M_psi_.data(), static_cast<int>(n * n), MPI_DOUBLE, MPI_SUM,
                comm_);
  // b_e^T psi_d: elongation of bar e under psi_d, from the rows at its ends.
  flexibility_.resize(n, n);
  for (long e = 0; e < n; ++e) {
    const auto& nodes = mesh.bars[bars[e]].nodes;
    for (long d = 0; d < n; ++d) {
      double dl = 0;
      for (int c = 0; c < 3; ++c)
        dl += direction[e][c] * (rows_(row_of(keys, basis_row_key(nodes[1], c)), d) -
                                 rows_(row_of(keys, basis_row_key(nodes[0], c)), d));
      flexibility_(e, d) = dl;
    }
  }
}

void DropperShapes::mass_products(const double* phis, long count, double* out) const {
  const long n = static_cast<long>(count_);
  product_tn(count, n, Mpsi_.rows(), phis, Mpsi_.data(), out, count);
  MPI_Allreduce(MPI_IN_PLACE, out, static_cast<int>(count * n), MPI_DOUBLE, MPI_SUM, comm_);
}

// Under a mean wind, phi^T C phi of each mode (C: the wires' aerodynamic
// damping, assembly/wind_terms.hpp); nothing without wind.
class WindDamping {
 public:
  explicit WindDamping(const assembly::CatenarySystem& system) {
    if (system.mesh().conditions.wind.any()) C_ = assembly::aerodynamic_damping_matrix(system);
  }
  ~WindDamping() { MatDestroy(&C_); }
  WindDamping(const WindDamping&) = delete;
  WindDamping& operator=(const WindDamping&) = delete;
  void append(Vec phi, std::vector<double>& out) const {
    if (C_) out.push_back(assembly::quadratic_form(C_, phi));
  }

 private:
  Mat C_ = nullptr;
};

// g_i = (K^-1)_zz at every contact-wire node, contact_wire_nodes() (0 where z is fixed).
std::vector<double> contact_compliance(const assembly::CatenarySystem& system,
                                       const StiffnessSolver& K) {
  const auto& mesh = system.mesh();
  const auto& L = system.layout();
  std::vector<double> g;
  Vec e = system.create_vector(), y = system.create_vector();
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(e, &lo, &hi));
  for (int node : catenary::contact_wire_nodes(mesh)) {
    const PetscInt dof = L.global_dof(node, 2);
    if (dof < 0) {
      g.push_back(0.0);
      continue;
    }
    PCSIM_PETSC(VecSet(e, 0.0));
    if (dof >= lo && dof < hi) PCSIM_PETSC(VecSetValue(e, dof, 1.0, INSERT_VALUES));
    PCSIM_PETSC(VecAssemblyBegin(e));
    PCSIM_PETSC(VecAssemblyEnd(e));
    K.solve(e, y);
    double compliance = 0;
    if (dof >= lo && dof < hi) PCSIM_PETSC(VecGetValues(y, 1, &dof, &compliance));
    MPI_Allreduce(MPI_IN_PLACE, &compliance, 1, MPI_DOUBLE, MPI_SUM, system.comm());
    g.push_back(compliance);
  }
  PCSIM_PETSC(VecDestroy(&e));
  PCSIM_PETSC(VecDestroy(&y));
  return g;
}

template <typename Matrix>
std::vector<double> row_major(const Matrix& A) {
  std::vector<double> out(static_cast<std::size_t>(A.size()));
  for (long i = 0; i < A.rows(); ++i)
    for (long j = 0; j < A.cols(); ++j) out[i * A.cols() + j] = A(i, j);
  return out;
}

}  // namespace

// What the data are computed with, kept between extend() calls.
struct ModalDataBuilder::Parts {
  assembly::CatenarySystem& system;
  Vec x;
  bool keep_vectors = true;
  bool rows_given_away = false;  // the data took the store's rows (give_back_rows)
  std::vector<long> row_keys;
  Operators op;
  RowGather rows;
  WindDamping wind_damping;
  std::unique_ptr<StiffnessSolver> K;
  std::unique_ptr<DropperShapes> shapes;
  std::unique_ptr<ShiftProducts> shift_products;  // every vector, for the window's shift
  // The window's vectors are appended as the first extend's modes, the
  // shapes, then the later extends' modes: the shapes start at this index.
  std::size_t shapes_appended_at = 0;
  std::vector<double> contact_compliance, omega2, wind;
  ModeRowStore mode_rows;                          // the modes' kept rows, as they come
  std::vector<double> gathered;                    // one mode's kept rows
  std::vector<std::vector<double>> mass_products;  // of each mode
  Eigen::MatrixXd pending;  // local parts of the modes whose mass products are to come
  long pending_count = 0;
  double cutoff_hz = 0, max_residual = 0;
  bool computed = false;

  Parts(assembly::CatenarySystem& s, Vec x_, bool full_shapes, Mat shift,
        const std::string& spill_dir, Mat loads)
      : system(s),
        x(x_),
        row_keys(catenary::reduced_basis_rows(s.mesh(), full_shapes)),
        op(s, x_),
        rows(s, row_keys, loads),
        wind_damping(s),
        mode_rows(row_keys.size()),
        gathered(rows.size()) {
    if (shift) shift_products = std::make_unique<ShiftProducts>(op.M, shift, spill_dir);
  }
  void add_mode(double lambda, Vec phi);
  void flush_mass_products();  // of the pending modes (collective)
  ModalData data();            // takes the modes' rows and the shift products
  void shapes_last(std::vector<double>& g, long c, bool to_end) const;
};

namespace {

Mat turbulence_loads(assembly::CatenarySystem& system) {
  const auto& wind = system.mesh().conditions.wind;
  return wind.any() && wind.turbulence.on ? assembly::turbulence_load_matrix(system) : nullptr;
}

}  // namespace

ModalDataBuilder::ModalDataBuilder(assembly::CatenarySystem& system, Vec x, bool full_shapes,
                                   Mat shift, const std::string& spill_dir) {
  Mat loads = turbulence_loads(system);
  parts_ = std::make_unique<Parts>(system, x, full_shapes, shift, spill_dir, loads);
  MatDestroy(&loads);  // (the gather holds it)
}

ModalDataBuilder::~ModalDataBuilder() = default;

double ModalDataBuilder::cutoff_hz() const {
  return parts_->computed ? parts_->cutoff_hz : -1;
}

long ModalDataBuilder::modes() const {
  return static_cast<long>(parts_->omega2.size());
}

long ModalDataBuilder::kept_rows() const {
  return static_cast<long>(parts_->row_keys.size());
}

long ModalDataBuilder::shapes() const {
  return parts_->shapes ? static_cast<long>(parts_->shapes->count()) : 0;
}

bool ModalDataBuilder::rows_given_away() const {
  return parts_->rows_given_away;
}

void ModalDataBuilder::give_back_rows(std::vector<double>&& mode_rows,
                                      std::vector<double>&& shift_products) {
  Parts& p = *parts_;
  const long c = static_cast<long>(p.omega2.size()) + shapes();
  if (mode_rows.size() != p.row_keys.size() * p.omega2.size() ||
      (p.shift_products && shift_products.size() != static_cast<std::size_t>(c * c)))
    throw SolverError("modal data: the rows given back are not the last data's");
  p.mode_rows.adopt(std::move(mode_rows), p.omega2.size());
  if (p.shift_products) {
    p.shapes_last(shift_products, c, false);
    p.shift_products->give_back(std::move(shift_products));
  }
  p.rows_given_away = false;
}

bool ModalDataBuilder::has_shift() const {
  return parts_->shift_products != nullptr;
}

void ModalDataBuilder::Parts::add_mode(double lambda, Vec phi) {
  if (shift_products) shift_products->append(phi);
  omega2.push_back(lambda);
  rows.gather(phi, gathered.data());
  mode_rows.append(gathered.data());
  if (shapes && shapes->count() > 0) {
    PetscInt local;
    PCSIM_PETSC(VecGetLocalSize(phi, &local));
    if (pending.cols() == 0) pending.resize(local, kProductBlock);
    copy_local(phi, pending.col(pending_count++).data());
    if (pending_count == kProductBlock) flush_mass_products();
  }
  wind_damping.append(phi, wind);
}

void ModalDataBuilder::Parts::flush_mass_products() {
  if (!shapes || shapes->count() == 0) return;
  const long n = static_cast<long>(shapes->count());
  Eigen::MatrixXd products(pending_count, n);
  shapes->mass_products(pending.data(), pending_count, products.data());
  for (long k = 0; k < pending_count; ++k) {
    mass_products.emplace_back(static_cast<std::size_t>(n));
    for (long d = 0; d < n; ++d) mass_products.back()[d] = products(k, d);
  }
  pending_count = 0;
}

ModalData ModalDataBuilder::extend(double max_frequency_hz, const ModalProgress& progress,
                                   bool keep_for_extension) {
  PetscLogDouble t0, t1;
  PetscTime(&t0);
  Parts& p = *parts_;
  if (p.computed && !p.keep_vectors) throw SolverError("modal data: the vectors were freed");
  if (p.rows_given_away) throw SolverError("modal data: the last data's rows not given back");
  p.keep_vectors = keep_for_extension;
  const bool complete = max_frequency_hz <= 0;
  if (p.computed && (complete || p.cutoff_hz <= 0 || max_frequency_hz < p.cutoff_hz))
    throw SolverError("modal data: a cut-off can only be raised");
  if (!p.computed && !complete) {
    p.K = std::make_unique<StiffnessSolver>(p.op.K);
    p.shapes = std::make_unique<DropperShapes>(p.system, p.x, p.op, *p.K, p.rows, p.row_keys);
    if (!p.system.mesh().contact_wire_list().empty())
      p.contact_compliance = contact_compliance(p.system, *p.K);
  }
  const auto sink = [&p](double lambda, Vec phi) { p.add_mode(lambda, phi); };
  // Once the modes are counted (and the basis found to fit): the rows' room
  // for them and for the droppers' Ritz vectors the basis adds.
  const std::size_t room = p.shapes ? p.shapes->count() : 0;
  const ModalProgress reserving = [&](long done, long total, int parts) {
    if (progress) progress(done, total, parts);
    if (done == 0) p.mode_rows.reserve_columns(p.omega2.size() + total + room);
  };
  const double omega_from = 2 * M_PI * p.cutoff_hz, omega_max = 2 * M_PI * max_frequency_hz;
  p.max_residual = std::max(p.max_residual,
                            complete ? stream_all_modes_dense(p.op, sink)
                                     : stream_modes(p.op, p.computed ? omega_from * omega_from : 0,
                                                    omega_max * omega_max, sink, reserving));
  p.flush_mass_products();
  Eigen::MatrixXd().swap(p.pending);
  if (p.shift_products && p.shapes && !p.computed) {
    p.shapes_appended_at = p.omega2.size();
    for (std::size_t d = 0; d < p.shapes->count(); ++d)
      p.shift_products->append(p.shapes->vector(d));
  }
  p.computed = true;
  p.cutoff_hz = max_frequency_hz;
  ModalData data = p.data();
  PetscTime(&t1);
  data.wall_time_s = t1 - t0;
  return data;
}

ModalData ModalDataBuilder::Parts::data() {
  ModalData data;
  data.cutoff_hz = cutoff_hz;
  data.row_keys = row_keys;
  data.omega2 = omega2;
  data.wind_damping = wind;
  data.max_relative_residual = max_residual;
  data.contact_compliance = contact_compliance;
  const std::size_t m = data.modes();
  const std::size_t nd = shapes ? shapes->count() : 0;
  // With room for the basis's rows (m + the droppers' Ritz vectors, at most
  // nd), which assemble_basis forms in place; a raise needs them back.
  data.mode_rows = mode_rows.take(nd);
  rows_given_away = keep_vectors;
  // What the eigensolver freed (its vectors, small blocks the C library
  // keeps) given back before the shift products are formed
  // (modal_basis_internal.hpp).
  malloc_trim(0);
  if (nd > 0) {
    data.shape_rows = row_major(shapes->rows());
    data.mode_shape_mass.resize(m * nd);
    for (std::size_t k = 0; k < m; ++k)
      std::copy(mass_products[k].begin(), mass_products[k].end(),
                data.mode_shape_mass.begin() + k * nd);
    data.shape_mass = row_major(shapes->psi_M_psi());
    data.shape_flexibility = row_major(shapes->flexibility());
  }
  if (shift_products) {
    shift_products->compute(x, keep_vectors);  // in the order appended
    // Moved, not copied (a raise needs them back: give_back_rows).
    data.shift_products = shift_products->take();
    shapes_last(data.shift_products, static_cast<long>(m + nd), true);
  }
  return data;
}

// The order appended, [first modes, shapes, later modes], to [modes,
// shapes] (to_end) or back: the shapes' rows and columns rotated, in place.
void ModalDataBuilder::Parts::shapes_last(std::vector<double>& g, long c, bool to_end) const {
  const long nd = shapes ? static_cast<long>(shapes->count()) : 0;
  const long s0 = static_cast<long>(shapes_appended_at), k = to_end ? nd : c - s0 - nd;
  for (long i = 0; i < c; ++i)
    std::rotate(g.begin() + i * c + s0, g.begin() + i * c + s0 + k, g.begin() + (i + 1) * c);
  std::rotate(g.begin() + s0 * c, g.begin() + (s0 + k) * c, g.end());
}

}  // namespace pcsim::simulation
