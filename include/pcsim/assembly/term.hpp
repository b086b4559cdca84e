// The term interface of the coupled second-order system
//   F(t, U, V, A) = sum over terms = 0
// (thesis 3.2-3.3: catenary forces, inertia, damping, dropper slack, penalty
// contact, pantographs). Every effect a scene switches on is one Term; an
// effect that is off is not in the list and costs nothing. A term never knows
// which integrator or solver calls it: it adds its residual and its tangent
//   dF/dU + shift_v dF/dV + shift_a dF/dA
// for the shifts the integrator gives.
//
// A term states its residual in two parts:
//  - linear_parts(): constant matrices times the state, F += A (cu dU + cv V + ca A)
//    with dU = U - U_ref (the static configuration). The coupled system merges
//    the parts that share a matrix (one product per matrix: K0 (dU + beta V),
//    M (A + alpha V)) and adds (cu + shift_v cv + shift_a ca) A to the tangent;
//  - add_residual()/add_tangent(): everything else (element forces, contact,
//    pantographs), added with ADD_VALUES before the caller assembles.
//
// For the cheap path (a constant step matrix J0 factored once) a term says
// how its tangent behaves (TangentKind). A 'low_rank' term adds a reference
// tangent to J0 and reports the change of its tangent against that reference
// as rank-one terms c u u^T (low_rank_change), which the solver adds exactly
// (Woodbury). A 'block' term (a nonlinear pantograph) has its tangent in a
// small dense block of unknowns that no reference tangent couples with any
// other: J0 holds its reference value, block_change() the exact change, which
// the solver refactors at every iteration. The solver never knows what a
// dropper, a contact or a pantograph is.
#pragma once

#include <petscmat.h>
#include <petscvec.h>

#include <Eigen/SparseCore>
#include <algorithm>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

namespace pcsim::assembly {

class CoupledState;

// J = dF/dU + v dF/dV + a dF/dA.
struct Shifts {
  double v = 0;
  double a = 0;
};

// F += matrix (cu (U - U_ref) + cv V + ca A); tangent += (cu + v cv + a ca) matrix.
struct LinearPart {
  Mat matrix = nullptr;
  double cu = 0, cv = 0, ca = 0;
  // Nonzero pattern of 'matrix' relative to the system's Jacobian.
  MatStructure structure = SAME_NONZERO_PATTERN;
};

// Entries that never change once made, shared by whoever copies them: a term
// that hands out the same u step after step (a window end's dashpot, a slack
// dropper's row over every mode) hands out the same entries, and a solver that
// keeps them neither copies nor compares them (== compares the pointers
// first). A modal u has every mode: 35 kB a term at 4406 vectors. Made from a
// vector (kept by the copies), or as a view of n entries that 'owner' keeps
// alive (a row of a kept matrix; no owner: entries that outlive every copy,
// a reduced catenary's own rows).
template <class T>
class SharedEntries {
 public:
  SharedEntries() = default;
  SharedEntries(std::vector<T> values) {  // NOLINT(google-explicit-constructor): as the vector was
    auto kept = std::make_shared<const std::vector<T>>(std::move(values));
    size_ = kept->size();
    data_ = std::shared_ptr<const T>(kept, kept->data());
  }
  SharedEntries(std::initializer_list<T> values) : SharedEntries(std::vector<T>(values)) {}
  SharedEntries(std::shared_ptr<const void> owner, const T* data, std::size_t n)
      : data_(std::move(owner), data), size_(n) {}
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const T& operator[](std::size_t i) const { return data_.get()[i]; }
  const T* data() const { return data_.get(); }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size(); }
  friend bool operator==(const SharedEntries& a, const SharedEntries& b) {
    return a.size() == b.size() &&
           (a.data() == b.data() || std::equal(a.begin(), a.end(), b.begin()));
  }
  friend bool operator!=(const SharedEntries& a, const SharedEntries& b) { return !(a == b); }

 private:
  std::shared_ptr<const T> data_;
  std::size_t size_ = 0;
};

// A rank-one change c u u^T of a tangent, u sparse (global indices, weights),
// identical on every rank. reuse_columns: the same indices recur over many
// steps (a contact moving along the wire), so J0^-1 e_g per index is worth
// caching; otherwise J0^-1 u is solved directly.
struct RankOne {
  int key = 0;  // identifies the term within its Term (a solver reuses J0^-1 u while u stays)
  SharedEntries<PetscInt> index;
  SharedEntries<double> weight;
  double coefficient = 0;
  bool reuse_columns = false;
  bool contiguous = false;  // index is index[0], index[0] + 1, ... (dense u over a block)
};

// The change J - J_ref of a tangent confined to the dense diagonal block of
// unknowns first .. first + size - 1, on the rank that owns them (key, first
// and size identical on every rank), as a dense change 'delta' or, from a
// model with sparse tangents, as the block's value J itself ('value', its
// nonzeros only); both empty on the other ranks.
struct BlockChange {
  int key = 0;  // identifies the block within its Term
  PetscInt first = 0;
  int size = 0;
  std::vector<double> delta;          // size x size, row-major
  Eigen::SparseMatrix<double> value;  // size x size (delta empty)
  bool given() const { return !delta.empty() || value.size() > 0; }
};

enum class TangentKind {
  constant,  // never changes: part of J0 for good
  low_rank,  // reference tangent in J0 + low_rank_change() (contact, slack droppers)
  block,     // reference tangent in J0 + block_change() (a nonlinear pantograph)
  varying,   // general nonlinear: needs the full Newton path
};

// Power of the non-conservative forces of a term (energy balance tests):
// dE/dt = external + dissipative.
struct TermPower {
  double dissipative = 0;  // <= 0 for passive elements (damping, friction)
  double external = 0;     // work rate of prescribed forces (moving contact, uplift)
};

// How a term's add_residual() (not its linear parts) depends on the acceleration A:
// not at all, through a constant matrix, or through a configuration-dependent mass
// M(t, U, V) ('varying'); add_inertia gives the product M A for both. Every term's
// residual is affine in A (the pantograph models': tests/pantograph), so the
// integrator may take its HHT alpha-term from the last residual.
enum class AccelerationUse { none, constant, varying };

// v^T C v over the ranks (a constant damping matrix C dissipates -v^T C v).
double quadratic_form(Mat C, Vec v);

class Term {
 public:
  virtual ~Term() = default;
  virtual std::string name() const = 0;
  virtual TangentKind tangent_kind() const = 0;

  virtual std::vector<LinearPart> linear_parts() const { return {}; }
  // Residual and tangent beyond the linear parts. add_residual adds either
  // with vector operations on the assembled F (scatters, AXPY) or, if
  // adds_by_set_values(), with VecSetValues(ADD_VALUES) only: the system calls
  // the former first and assembles F once after the latter. add_tangent adds
  // with MatSetValues(ADD_VALUES); the system assembles J.
  virtual bool adds_by_set_values() const { return false; }
  virtual void add_residual(const CoupledState& state, Vec F) {}
  virtual void add_tangent(const CoupledState& state, Shifts shifts, Mat J) {}
  // Every term whose add_residual() reads A says so (default: it does not).
  virtual AccelerationUse acceleration_use() const { return AccelerationUse::none; }
  // 'constant' and 'varying': F += dF/dA A for add_residual()'s part, dF/dA at
  // the state (by VecSetValues if adds_by_set_values(), as add_residual does),
  // on entries this rank owns only: the system assembles it without
  // communication.
  virtual void add_inertia(const CoupledState& state, Vec A, Vec F) const {}
  // Entries the term may ever touch (zeros), so that the Jacobian's pattern
  // never changes during a run.
  virtual void insert_pattern(Mat J) const {}

  // Cheap path: the tangent that goes into J0 (default: the exact one) and
  // the change of the exact tangent against it, as rank-one terms. Called on
  // every rank (collective).
  virtual void add_reference_tangent(const CoupledState& state, Shifts shifts, Mat J) {
    add_tangent(state, shifts, J);
  }
  // Returns false when the change has grown too large to be worth it: the
  // solver then rebuilds J0 at the current state.
  virtual bool low_rank_change(const CoupledState& state, std::vector<RankOne>& terms) {
    return true;
  }
  // Values low_rank_change() needs summed over the ranks (which bars are
  // taut, whether a contact is closed): the term appends this rank's part,
  // the same count on every rank; the system sums every term's in one
  // reduction and gives each its sums back before low_rank_change()
  // (CoupledSystem::low_rank_change, the only caller).
  virtual void append_low_rank_sums(const CoupledState& state, std::vector<double>& local) const {}
  virtual void take_low_rank_sums(const double* sums) {}
  // 'block' terms: the change of the exact tangent (shifts as J0's) against
  // the reference one, on its own unknowns only (collective).
  virtual void block_change(const CoupledState& state, Shifts shifts,
                            std::vector<BlockChange>& blocks) {}

  // Checkpoint/restart: the state the term keeps between calls that is not a
  // function of the state vectors (e.g. rank-one terms frozen when a dropper
  // switched), so that a restarted run solves exactly what the uninterrupted
  // one would. Identical on every rank. restore() is called after the
  // reference tangent has been rebuilt at the checkpoint's J0 state.
  virtual std::vector<double> checkpoint() const { return {}; }
  virtual void restore(const std::vector<double>& state) {}

  // Energy stored by the term (kinetic or potential) and the power of its
  // non-conservative forces, summed over ranks (collective).
  virtual double energy(const CoupledState& state) const { return 0; }
  virtual TermPower power(const CoupledState& state) const { return {}; }
};

}  // namespace pcsim::assembly
