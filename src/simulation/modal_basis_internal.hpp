// Pieces of the reduced-basis computation (modal_basis.cpp drives them):
// the catenary's operators at the static configuration, the kept rows of a
// global vector, the eigenpairs of an interval streamed one by one.
#pragma once

#include <petscksp.h>

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/catenary/reduced_basis.hpp"

namespace pcsim::simulation::modal_detail {

// K_T (every term) and M of the catenary at x; symmetric.
struct Operators {
  Mat K = nullptr, M = nullptr;
  Operators(assembly::CatenarySystem& system, Vec x);
  ~Operators();
  Operators(const Operators&) = delete;
  Operators& operator=(const Operators&) = delete;
};

// The kept rows (catenary::basis_row_key) of global vectors, on every rank;
// a turbulence row (catenary::turbulence_row_keys) is the product with its
// column of 'loads' (assembly::turbulence_load_matrix), a generalised force.
class RowGather {
 public:
  RowGather(const assembly::CatenarySystem& system, const std::vector<long>& keys,
            Mat loads = nullptr);
  ~RowGather();
  RowGather(const RowGather&) = delete;
  RowGather& operator=(const RowGather&) = delete;
  // out[keys.size()]: the values of the rows (0 for constrained DOFs).
  void gather(Vec v, double* out) const;
  std::size_t size() const { return size_; }

 private:
  VecScatter scatter_ = nullptr;
  Vec local_ = nullptr;
  std::vector<std::size_t> slot_;  // row of each scattered value
  std::size_t size_ = 0;
  // Turbulence rows: L^T v (column layout), gathered to every rank, into
  // the rows from load_slot_ on.
  Mat loads_ = nullptr;
  Vec forces_ = nullptr, forces_all_ = nullptr;
  VecScatter to_all_ = nullptr;
  std::size_t load_slot_ = 0;
};

// Called with each eigenpair (lambda, phi), phi M-normalised with its largest
// component positive, in ascending order of lambda.
using ModeSink = std::function<void(double lambda, Vec phi)>;

// Every eigenpair of K phi = lambda M phi with lambda in [0, lambda_max],
// computed in chunks of the interval (options prefix -modal_); returns the
// largest relative residual ||K phi - lambda M phi|| / (lambda ||M phi||).
// progress(done, total) after each chunk (may be empty).
double stream_modes(const Operators& op, double lambda_max, const ModeSink& sink,
                    const std::function<void(long, long)>& progress);

// G = V^T M S V (row-major, c x c, every rank) over the vectors V appended
// (c of them, their local parts kept: n x c doubles in all): a moving
// window's shift in the computed vectors (ModalData::shift_products).
class ShiftProducts {
 public:
  ShiftProducts(Mat M, Mat S);
  void append(Vec v);
  // Collective; 'like' a vector of the layout. Frees the columns.
  std::vector<double> compute(Vec like);

 private:
  static constexpr long kBlock = 256;
  Mat M_, S_;
  PetscInt local_ = 0;
  long count_ = 0;
  std::vector<Eigen::MatrixXd> blocks_;  // local_ x kBlock each, the last partly filled
};

// Every eigenpair of a small structure by a dense solve on every rank.
double stream_all_modes_dense(const Operators& op, const ModeSink& sink);

}  // namespace pcsim::simulation::modal_detail
