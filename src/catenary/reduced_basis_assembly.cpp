// assemble_basis (reduced_basis.hpp): a reduced basis from cached modal data.
#include <malloc.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>

#include "pcsim/catenary/reduced_basis.hpp"
#include "pcsim/core/dense_gemm.hpp"
#include "pcsim/core/profiling.hpp"
#include "pcsim/core/union_find.hpp"

namespace pcsim::catenary {

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ConstMap = Eigen::Map<const RowMatrix>;

long row_of(const std::vector<long>& keys, long key) {
  const auto it = std::lower_bound(keys.begin(), keys.end(), key);
  if (it == keys.end() || *it != key) throw std::logic_error("reduced basis: a row is missing");
  return it - keys.begin();
}

// Contact-wire z rows, at contact_wire_nodes().
std::vector<long> contact_rows(const ModalData& data, const CatenaryMesh& mesh) {
  std::vector<long> rows;
  for (int n : contact_wire_nodes(mesh)) rows.push_back(row_of(data.row_keys, basis_row_key(n, 2)));
  return rows;
}

// The modes to keep: below the cut-off and, with vertical_only, those whose
// largest contact-wire vertical amplitude reaches s.participation of the
// largest one's.
std::vector<long> selected_modes(const ModalData& data, const CatenaryMesh& mesh,
                                 const ModalSettings& s, int& dropped) {
  const ConstMap rows(data.mode_rows.data(), static_cast<long>(data.row_keys.size()),
                      static_cast<long>(data.modes()));
  const double omega_max = 2 * M_PI * s.max_frequency_hz;
  std::vector<double> amplitude(data.modes(), 0.0);
  if (s.vertical_only)
    for (long r : contact_rows(data, mesh))
      for (long k = 0; k < rows.cols(); ++k)
        amplitude[k] = std::max(amplitude[k], std::abs(rows(r, k)));
  const double largest =
      amplitude.empty() ? 0.0 : *std::max_element(amplitude.begin(), amplitude.end());
  std::vector<long> keep;
  dropped = 0;
  for (long k = 0; k < rows.cols(); ++k) {
    if (s.max_frequency_hz > 0 && data.omega2[k] > omega_max * omega_max) continue;
    if (s.vertical_only && amplitude[k] < s.participation * largest) {
      ++dropped;
      continue;
    }
    keep.push_back(k);
  }
  return keep;
}

// The Ritz vectors of Kp x = omega^2 Mp x on the range of Mp (its
// eigenvalues above 'floor', or 1e-10 of its largest when floor is 0), as
// columns of coefficients over the shapes; their omega^2 appended.
Eigen::MatrixXd group_ritz(const Eigen::MatrixXd& Mp, const Eigen::MatrixXd& Kp, double floor,
                           std::vector<double>& omega2) {
  const long nd = Mp.rows();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> mass(Mp);
  if (floor <= 0) floor = 1e-10 * mass.eigenvalues().cwiseAbs().maxCoeff();
  std::vector<long> range;
  for (long j = 0; j < nd; ++j)
    if (mass.eigenvalues()[j] > floor) range.push_back(j);
  Eigen::MatrixXd T(nd, static_cast<long>(range.size()));
  for (std::size_t j = 0; j < range.size(); ++j)
    T.col(static_cast<long>(j)) =
        mass.eigenvectors().col(range[j]) / std::sqrt(mass.eigenvalues()[range[j]]);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(T.transpose() * Kp * T);
  for (long j = 0; j < solver.eigenvalues().size(); ++j) omega2.push_back(solver.eigenvalues()[j]);
  return T * solver.eigenvectors();
}

// The Ritz vectors as combinations of the computed vectors: Psi X - Phi_keep CX.
struct RitzCoefficients {
  RowMatrix C;            // kept modes x shapes: phi_k^T M psi_d
  Eigen::MatrixXd X, CX;  // shapes x r, kept modes x r
};

// The shapes' groups that Mp and Kp join (exact nonzeros): a line's tension
// sections' droppers apart, whose Ritz vectors then stay each on its section
// (one Rayleigh-Ritz over every shape mixes sections whose values are close,
// and the basis's columns could not be told apart by blocks:
// order_columns_by_block). In the order of their first shapes.
std::vector<std::vector<long>> shape_groups(const Eigen::MatrixXd& Mp, const Eigen::MatrixXd& Kp) {
  const long nd = Mp.rows();
  std::vector<long> parent(static_cast<std::size_t>(nd));
  std::iota(parent.begin(), parent.end(), 0L);
  for (long i = 0; i < nd; ++i)
    for (long j = i + 1; j < nd; ++j)
      if (Mp(i, j) != 0 || Kp(i, j) != 0) {
        const long a = core::find_root(parent, i), b = core::find_root(parent, j);
        parent[std::max(a, b)] = std::min(a, b);  // the smaller shape is the root
      }
  std::vector<long> group(static_cast<std::size_t>(nd), -1);  // by root
  std::vector<std::vector<long>> groups;
  for (long s = 0; s < nd; ++s) {  // a root is its group's first shape
    const long root = core::find_root(parent, s);
    if (group[root] < 0) {
      group[root] = static_cast<long>(groups.size());
      groups.emplace_back();
    }
    groups[group[root]].push_back(s);
  }
  return groups;
}

// Ritz vectors of the shapes' M-complement of the kept modes (header), group
// by group of shapes: their coefficients, their omega^2 appended to 'omega2'.
RitzCoefficients ritz_vectors(const ModalData& data, const std::vector<long>& keep,
                              std::vector<double>& omega2) {
  const long nd = static_cast<long>(data.shapes()), m = static_cast<long>(keep.size());
  const ConstMap all_C(data.mode_shape_mass.data(), static_cast<long>(data.modes()), nd);
  RitzCoefficients ritz;
  RowMatrix& C = ritz.C;
  C.resize(m, nd);
  Eigen::VectorXd w2(m);
  for (long i = 0; i < m; ++i) {
    C.row(i) = all_C.row(keep[i]);
    w2[i] = data.omega2[keep[i]];
  }
  Eigen::MatrixXd Mp = ConstMap(data.shape_mass.data(), nd, nd) - C.transpose() * C;
  Eigen::MatrixXd Kp =
      ConstMap(data.shape_flexibility.data(), nd, nd) - C.transpose() * w2.asDiagonal() * C;
  Mp = 0.5 * (Mp + Mp.transpose()).eval();
  Kp = 0.5 * (Kp + Kp.transpose()).eval();
  const auto groups = shape_groups(Mp, Kp);
  if (groups.size() == 1) {
    ritz.X = group_ritz(Mp, Kp, 0, omega2);
  } else {
    const double floor =
        1e-10 * Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Mp, Eigen::EigenvaluesOnly)
                    .eigenvalues()
                    .cwiseAbs()
                    .maxCoeff();
    std::vector<Eigen::MatrixXd> parts;
    long r = 0;
    for (const auto& g : groups) {
      const long n = static_cast<long>(g.size());
      Eigen::MatrixXd Mg(n, n), Kg(n, n);
      for (long i = 0; i < n; ++i)
        for (long j = 0; j < n; ++j) Mg(i, j) = Mp(g[i], g[j]), Kg(i, j) = Kp(g[i], g[j]);
      parts.push_back(group_ritz(Mg, Kg, floor, omega2));
      r += parts.back().cols();
    }
    ritz.X.setZero(nd, r);
    long col = 0;
    for (std::size_t k = 0; k < groups.size(); ++k) {
      for (std::size_t i = 0; i < groups[k].size(); ++i)
        ritz.X.block(groups[k][i], col, 1, parts[k].cols()) = parts[k].row(static_cast<long>(i));
      col += parts[k].cols();
    }
  }
  ritz.CX = C * ritz.X;
  return ritz;
}

// The kept modes' columns of 'rows' (nr x modes, row-major) moved in place
// to the first m of each row of stride c >= modes: the rows from the last,
// each through a row's buffer (a row's destination starts at or after its
// source, and no earlier row's source reaches it).
void move_kept_columns(std::vector<double>& rows, long nr, long modes,
                       const std::vector<long>& keep, long c) {
  const long m = static_cast<long>(keep.size());
  rows.resize(static_cast<std::size_t>(nr * c));  // within the capacity the data reserved
  std::vector<double> row(static_cast<std::size_t>(m));
  for (long i = nr - 1; i >= 0; --i) {
    const double* source = rows.data() + i * modes;
    for (long k = 0; k < m; ++k) row[k] = source[keep[k]];
    std::copy(row.begin(), row.end(), rows.data() + i * c);
  }
}

// The basis's rows [Phi_keep, (Psi - Phi_keep C) X] (nr x (m + r)), the kept
// modes' columns read from 'mode_rows' (nr x modes). With 'release' (the
// data's own mode rows, assemble_basis(ModalData&&)) and a basis at least as
// wide as the data, they are formed in the data's storage, which the data
// reserve for it (ModalDataBuilder): one copy of the rows, not two, where a
// first run's basis peaks; else the rows are copied and 'release' freed after.
void fill_rows(const ModalData& data, const std::vector<long>& keep, const RitzCoefficients& ritz,
               std::vector<double>* release, std::vector<double>& out) {
  const long nr = static_cast<long>(data.row_keys.size()), m = static_cast<long>(keep.size());
  const long r = ritz.X.cols(), c = m + r, modes = static_cast<long>(data.modes());
  if (release && c >= modes) {
    move_kept_columns(*release, nr, modes, keep, c);
    out = std::move(*release);
  } else {
    out.resize(static_cast<std::size_t>(nr * c));
    const ConstMap all_rows(data.mode_rows.data(), nr, modes);
    Eigen::Map<RowMatrix> rows(out.data(), nr, c);
    for (long i = 0; i < nr; ++i)  // row by row: both are row-major (a column copy strides)
      for (long k = 0; k < m; ++k) rows(i, k) = all_rows(i, keep[k]);
    if (release) std::vector<double>().swap(*release);
  }
  if (r == 0) return;
  // Row-major blocks as the BLAS's column-major transposes (dense_gemm).
  const long nd = static_cast<long>(data.shapes());
  std::vector<double> complement(data.shape_rows);  // Psi - Phi_keep C, nr x nd
  dense_gemm(false, false, nd, nr, m, -1.0, ritz.C.data(), nd, out.data(), c, 1.0,
             complement.data(), nd);
  dense_gemm(true, false, r, nr, nd, 1.0, ritz.X.data(), nd, complement.data(), nd, 0.0,
             out.data() + m, c);  // (Psi - Phi_keep C) X
}

// The window's shift in the basis B = [Phi_keep, Psi X - Phi_keep CX]:
// P = T^T G T from G = V^T M S V over the computed vectors V = [Phi, Psi]
// (row-major, total x total), T = [E_keep, -E_keep CX; 0, X] (E_keep: the
// kept modes, ascending), formed in G's own storage: G T by blocks of rows
// into each row's first c = m + r entries, then T^T (G T) by moving the kept
// rows up and appending the r Ritz rows. Peak: G and blocks of 256 rows
// (G T and P were copies of G's size each).
std::vector<double> shift_in_basis(std::vector<double> g, long total, long modes,
                                   const std::vector<long>& keep, const RitzCoefficients& ritz) {
  using Rows = Eigen::Map<RowMatrix, 0, Eigen::OuterStride<>>;
  constexpr long kRows = 256;
  const long nd = total - modes, m = static_cast<long>(keep.size()), r = ritz.X.cols();
  const long c = m + r;
  const Eigen::OuterStride<> stride(total);
  RowMatrix block(kRows, c);
  for (long i0 = 0; i0 < total; i0 += kRows) {  // (G T)(i, :) into G(i, 0:c)
    const long n = std::min(kRows, total - i0);
    Rows rows(g.data() + i0 * total, n, total, stride);
    for (long i = 0; i < m; ++i) block.col(i).head(n) = rows.col(keep[i]);
    if (r > 0) {  // G(rows, shapes) X - (G T)(rows, kept) CX, as the BLAS's transposes
      dense_gemm(true, false, r, n, nd, 1.0, ritz.X.data(), nd, rows.data() + modes, total, 0.0,
                 block.data() + m, c);
      dense_gemm(true, false, r, n, m, -1.0, ritz.CX.data(), m, block.data(), c, 1.0,
                 block.data() + m, c);
    }
    rows.leftCols(c) = block.topRows(n);
  }
  RowMatrix bottom(r, c);  // X^T (G T)(shapes, :) - CX^T (G T)(keep, :)
  if (r > 0) {
    dense_gemm(false, false, c, r, nd, 1.0, g.data() + modes * total, total, ritz.X.data(), nd, 0.0,
               bottom.data(), c);
    for (long i0 = 0; i0 < m; i0 += kRows) {
      const long n = std::min(kRows, m - i0);
      for (long i = 0; i < n; ++i)
        block.row(i) = Rows(g.data() + keep[i0 + i] * total, 1, c, stride);
      dense_gemm(false, false, c, r, n, -1.0, block.data(), c, ritz.CX.data() + i0, m, 1.0,
                 bottom.data(), c);
    }
  }
  // Row i of P from row keep[i] >= i of G T: no later source is overwritten.
  for (long i = 0; i < m; ++i)
    std::memmove(g.data() + i * c, g.data() + keep[i] * total, sizeof(double) * c);
  std::copy(bottom.data(), bottom.data() + bottom.size(), g.data() + m * c);
  g.resize(static_cast<std::size_t>(c * c));  // kept only until rounded to float (assemble)
  return g;
}

// assemble_basis with the data's shift products given apart (moved or
// copied); the data's mode rows freed once read when 'release' is theirs.
ReducedBasis assemble(const ModalData& data, std::vector<double> shift_products,
                      std::vector<double>* release, const CatenaryMesh& mesh,
                      const ModalSettings& s) {
  const ScopedEvent timed(log_events().basis_assembly);
  if (s.max_frequency_hz > data.cutoff_hz * (1 + 1e-12) && data.cutoff_hz > 0)
    throw std::logic_error("reduced basis: the data stop below the cut-off asked for");
  ReducedBasis b;
  b.cutoff_hz = s.max_frequency_hz;
  b.row_keys = data.row_keys;
  const std::vector<long> keep = selected_modes(data, mesh, s, b.dropped_modes);
  const long m = static_cast<long>(keep.size());
  for (long i = 0; i < m; ++i) b.omega2.push_back(data.omega2[keep[i]]);
  b.eigenmodes = static_cast<int>(m);
  RitzCoefficients ritz;
  if (s.dropper_shapes && data.shapes() > 0) ritz = ritz_vectors(data, keep, b.omega2);
  if (data.wind_damping.size() == data.modes()) {
    b.wind_damping.assign(b.omega2.size(), 0.0);
    for (long i = 0; i < m; ++i) b.wind_damping[i] = data.wind_damping[keep[i]];
  }
  const std::size_t vectors = data.modes() + data.shapes();
  const long modes = static_cast<long>(data.modes());
  fill_rows(data, keep, ritz, release, b.rows);
  // The data's rows freed: given back before the shift is formed (in pcsim's
  // processes the C library keeps freed blocks; simulation/modal_basis_internal.hpp).
  if (release) malloc_trim(0);
  if (!shift_products.empty() && shift_products.size() == vectors * vectors) {
    const auto P =
        shift_in_basis(std::move(shift_products), static_cast<long>(vectors), modes, keep, ritz);
    b.shift.assign(P.begin(), P.end());  // rounded to nearest (reduced_basis.hpp)
  }
  if (!mesh.contact_wire_list().empty()) {
    const Eigen::Map<const RowMatrix> rows(b.rows.data(), static_cast<long>(b.row_keys.size()),
                                           static_cast<long>(b.omega2.size()));
    const auto cw = contact_rows(data, mesh);
    b.contact_flexibility.assign(cw.size(), 0.0);
    if (s.contact_flexibility && data.contact_compliance.size() == cw.size())
      for (std::size_t i = 0; i < cw.size(); ++i) {
        double r = data.contact_compliance[i];
        for (long k = 0; k < rows.cols(); ++k) r -= rows(cw[i], k) * rows(cw[i], k) / b.omega2[k];
        b.contact_flexibility[i] = std::max(r, 0.0);
      }
  }
  order_columns_by_block(b);
  return b;
}

}  // namespace

ReducedBasis assemble_basis(const ModalData& data, const CatenaryMesh& mesh,
                            const ModalSettings& settings) {
  return assemble(data, data.shift_products, nullptr, mesh, settings);
}

ReducedBasis assemble_basis(ModalData&& data, const CatenaryMesh& mesh,
                            const ModalSettings& settings) {
  std::vector<double> shift_products = std::move(data.shift_products);
  return assemble(data, std::move(shift_products), &data.mode_rows, mesh, settings);
}

}  // namespace pcsim::catenary
