// The catenary's fidelity levels and the reduced (modal) basis of the
// linearised catenary: plain data filled by the solver driver
// (solvers/modal_basis.hpp), cached by output/modal_cache.hpp and used by the
// modal catenary model (assembly/modal_catenary.hpp).
//
// The basis: the modes of K_T phi = omega^2 M phi about the static
// configuration below a cut-off, optionally followed by Ritz vectors of the
// droppers' static shapes K^-1 b_d (restore the droppers' truncated
// flexibility); all M-orthonormal and K-diagonal. Only the rows of the basis
// the model needs are kept (contact-wire z and z', bar ends, supports; every
// node's position only for field snapshots), not the n x m matrix.
// Rows of constrained DOFs are zero.
#pragma once

#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"

namespace pcsim::catenary {

enum class CatenaryFidelity { nonlinear, linear, modal };
const char* fidelity_name(CatenaryFidelity f);

// How the modal model treats its droppers and which ingredients it uses
// (the scene's `catenary: {model: modal, ...}`; docs/fidelity.md).
struct ModalSettings {
  double max_frequency_hz = 0;      // cut-off; <= 0: every mode (small structures only)
  bool dropper_shapes = true;       // augment the modes with the droppers' static shapes
  bool contact_flexibility = true;  // series spring of the contact point's residual flexibility
  bool vertical_only = false;   // leave out modes the contact wire's vertical motion hardly shows
  double participation = 0.03;  // vertical_only: threshold (kVerticalParticipation)
  enum class DropperCheck { bounded, all } dropper_check = DropperCheck::bounded;
  // slack: linear bars + the slack correction -k min(dl, 0) (rank one);
  // slack_exact: + a slack 'force' bar's geometric stiffness removed (its
  // force exactly zero; three rank-one terms); exact: every bar's nonlinear
  // force minus its linearisation (full path).
  enum class Bars { slack, slack_exact, exact } bars = Bars::slack_exact;
  // > 0: droppers within this distance of a pantograph's contact point [m]
  // take their exact force, taut or slack, not its linearisation
  // (assembly/modal_terms.hpp, ModalExactDroppers); 0: none.
  double exact_droppers_within = 0;
  bool full_shapes = false;  // keep every node's position rows (field snapshots)
  // How the line is reduced (catenary.modal.method): automatic (the run
  // scene chooses: run_scene.hpp), the whole line's basis, or a moving
  // window's basis (catenary/window.hpp) shifted with the train.
  enum class Method { automatic, whole, window } method = Method::automatic;
};
const char* modal_method_name(ModalSettings::Method m);

// A catenary mode of frequency f shows in the contact force of a pantograph
// at speed v on a wire of wave speed c at about f (1 - v/c): the modes up to
// filter_hz / (1 - v/c) make the filtered force.
inline double doppler_frequency(double filter_hz, double speed, double wave_speed) {
  return filter_hz / (1.0 - speed / wave_speed);
}
// Default modal cut-off over that frequency (measured: docs/fidelity.md).
constexpr double kModalCutoffMargin = 1.1;

// A row of the basis: DOF c (0..5) of node n, stored as 6 n + c.
inline long basis_row_key(int node, int c) {
  return 6L * node + c;
}

// What the eigensolve and the static solves of a catenary give (computed by
// solvers/modal_basis.hpp, cached by output/modal_cache.hpp): every mode
// below cutoff_hz and the droppers' static shapes psi_d = K^-1 b_d, as the
// kept rows only. Any basis with a lower cut-off, fewer modes or fewer
// ingredients is assembled from it (assemble_basis) without solving again.
struct ModalData {
  double cutoff_hz = 0;                    // <= 0: every mode of the structure
  std::vector<double> omega2;              // of the modes, ascending
  std::vector<long> row_keys;              // the kept rows (basis_row_key), ascending
  std::vector<double> mode_rows;           // row-major, row_keys.size() x omega2.size()
  std::vector<double> shape_rows;          // row-major, row_keys.size() x shapes (psi_d)
  std::vector<double> mode_shape_mass;     // phi_k^T M psi_d, modes x shapes
  std::vector<double> shape_mass;          // psi_d^T M psi_e, shapes x shapes
  std::vector<double> shape_flexibility;   // b_d^T psi_e = b_d^T K^-1 b_e, shapes x shapes
  std::vector<double> contact_compliance;  // (K^-1)_zz at contact_wire_nodes()
  // A moving window's shift (catenary/window.hpp): G = V^T M S V over the
  // vectors V = [modes, shapes] (S: the displacement field moved back by the
  // window's period, zero where it comes from beyond the window's front),
  // (modes + shapes)^2 row-major; empty without a window.
  std::vector<double> shift_products;
  // Under a mean wind, phi_k^T C phi_k of every mode with C the wires'
  // aerodynamic damping (assembly/wind_terms.hpp) [1/s]; empty without wind.
  std::vector<double> wind_damping;
  double max_relative_residual = 0;  // of the eigenpairs
  double wall_time_s = 0;            // to compute it (0 when read from the cache)
  std::size_t modes() const { return omega2.size(); }
  std::size_t shapes() const { return row_keys.empty() ? 0 : shape_rows.size() / row_keys.size(); }
};

// The basis the modal model uses: M-orthonormal, K-diagonal.
struct ReducedBasis {
  // Modes below the cut-off: basis vectors 0..eigenmodes-1 in one block;
  // with several blocks (column_blocks) each block's modes, then its others.
  int eigenmodes = 0;
  int dropped_modes = 0;       // modes below the cut-off left out (vertical_only)
  std::vector<double> omega2;  // omega_k^2 of every basis vector
  std::vector<long> row_keys;  // the kept rows (basis_row_key), ascending
  std::vector<double> rows;    // row-major, row_keys.size() x size()
  // Contact point's residual flexibility r = g(x,x) - sum_k phi_k(x)^2 / omega_k^2
  // at contact_wire_nodes() [m/N] (0 when not computed).
  std::vector<double> contact_flexibility;
  // A moving window's shift in the basis: eta' = P eta with P = B^T M S B
  // (the M-projection of the shifted field), size() x size() row-major,
  // rounded to single precision (the pass over it is bound by memory: half
  // the bytes; its rounding, 2^-24 of an entry, is far below what the
  // projection on a truncated basis loses); empty without a window.
  std::vector<float> shift;
  // The diagonal of the wires' aerodynamic damping in the basis, size() [1/s]:
  // the modes' phi_k^T C phi_k; 0 for the droppers' Ritz vectors (above the
  // cut-off, where it damps by less than rho Cd d V / (2 mu omega): 0.03 %
  // at 25 m/s and 70 Hz). Empty without wind.
  std::vector<double> wind_damping;
  double cutoff_hz = 0;
  // The columns in blocks that share no nonzero kept row (a line's tension
  // sections, each with its own modes): block i is columns column_blocks[i]
  // .. column_blocks[i + 1] - 1, the last entry size(). {0, size()}: one
  // block; empty: not known (one block).
  std::vector<long> column_blocks;
  std::size_t size() const { return omega2.size(); }
};

// Reorders b's columns (omega2, rows, wind_damping) block after block, each
// block's columns in their order, the blocks in the order of their first
// columns, and sets b.column_blocks (a basis with a shift is left as it is,
// one block). Exact zeros tell the blocks apart: the modes of a structure's
// parts computed each on its own DOFs (simulation/modal_basis.hpp).
void order_columns_by_block(ReducedBasis& b);

// The basis for 'settings' from data computed at a cut-off at least as high:
// the modes below settings.max_frequency_hz (with vertical_only those whose
// largest contact-wire vertical amplitude reaches settings.participation of
// the largest mode's), then, with dropper_shapes, the Ritz
// vectors of the shapes' M-complement of the kept modes (Psi' = Psi - Phi C,
// M' = Psi^T M Psi - C^T C, K' = Psi^T K Psi - C^T Omega^2 C; K' X = M' X
// Lambda on the range of M': with exact eigenvectors the Rayleigh-Ritz on
// [Phi, Psi]); with contact_flexibility the residual flexibility at the
// contact-wire nodes.
ReducedBasis assemble_basis(const ModalData& data, const CatenaryMesh& mesh,
                            const ModalSettings& settings);
// The same, consuming the data's shift products (the window's shift is
// formed in their storage: no copy of their size).
ReducedBasis assemble_basis(ModalData&& data, const CatenaryMesh& mesh,
                            const ModalSettings& settings);

// The nodes of every contact wire, wire after wire (mesh.contact_wire_list()
// order): the order of the contact compliance and residual flexibility.
std::vector<int> contact_wire_nodes(const CatenaryMesh& mesh);

// The rows a modal model of 'mesh' needs: z and z' of the contact-wire nodes
// (under a wind y and y' too: the contact point's lateral motion),
// x, y, z of every bar's ends, z of the supports, the DOFs of its dashpots
// and pins (a window's ends); with full_shapes x, y, z of every node.
// Sorted, unique.
std::vector<long> reduced_basis_rows(const CatenaryMesh& mesh, bool full_shapes);

}  // namespace pcsim::catenary
