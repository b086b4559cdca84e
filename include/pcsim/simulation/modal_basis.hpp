// The modal data of the linearised catenary (catenary/reduced_basis.hpp),
// from which reduced bases are assembled:
//  1. modes of K_T phi = omega^2 M phi about the static configuration below
//     the cut-off (SLEPc spectrum slicing with MUMPS, as `pcsim modes`), in
//     chunks of the interval so that only one chunk's vectors are held;
//  2. the droppers' static shapes psi_d = K^-1 b_d (b_d: the gradient of
//     dropper d's elongation), their mass products with the modes and each
//     other and their flexibilities b^T K^-1 b (the Rayleigh-Ritz ingredients);
//  3. the static compliance (K^-1)_zz at every contact-wire node.
// One Cholesky factorisation of K serves 2 and 3. Only the kept rows of the
// vectors are stored. max_frequency_hz <= 0: every mode of a small structure
// by a dense solve (the basis is then complete: no shapes, no compliance).
#pragma once

#include <petscvec.h>

#include <functional>
#include <memory>
#include <string>

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/catenary/reduced_basis.hpp"

namespace pcsim::simulation {

// The data computed in steps of a rising cut-off: extend(f) computes the
// modes below f, and after extend(f1 < f) only those between f1 and f. It
// keeps the operators, the factor of K, the dropper shapes and the
// compliance (and with a shift, every vector) until it is destroyed (the
// accuracy pilot's raised cut-offs, catenary_setup.hpp). The modes' kept
// rows and a window's shift products it does not keep: the data take them
// (the basis is formed in their storage), and a later extend needs them
// given back (give_back_rows: the caller reads them from where it stored
// the data), so that they are held once, not twice, while the lower
// cut-off's basis serves.
// 'x': the static configuration of 'system' (no extra unknowns); 'system'
// and 'x' must outlive it. Collective; the results on every rank.
// progress(done, total, parts): the modes computed so far, after each chunk of the
// interval (not for 'every mode'). shift: a moving window's shift S (global
// DOFs of 'system', S(g, h) = 1 where DOF g takes DOF h's displacement), or
// null; with it the data's shift_products, from every vector: n x (modes +
// shapes) doubles, kept on an unlinked file in spill_dir (the modal cache
// folder) but for the block being filled (in memory if spill_dir is "" or
// takes no file).
// parts: the groups of the structure whose modes are computed apart (its
// tension sections, which share no element; 1: the whole at once).
using ModalProgress = std::function<void(long done, long total, int parts)>;
class ModalDataBuilder {
 public:
  ModalDataBuilder(assembly::CatenarySystem& system, Vec x, bool full_shapes, Mat shift,
                   const std::string& spill_dir);
  ~ModalDataBuilder();
  ModalDataBuilder(const ModalDataBuilder&) = delete;
  ModalDataBuilder& operator=(const ModalDataBuilder&) = delete;
  // Collective. max_frequency_hz at least the last one's (<= 0, every mode:
  // only at the first call); wall_time_s is this call's. keep_for_extension
  // false: the window's vectors and products are freed as soon as they have
  // served (no later extend).
  catenary::ModalData extend(double max_frequency_hz, const ModalProgress& progress,
                             bool keep_for_extension);
  double cutoff_hz() const;  // the last extend's; -1 before the first
  long modes() const;        // computed so far
  long kept_rows() const;    // of every vector
  long shapes() const;       // the droppers' static shapes (0 before the first extend)
  // The last extend's data.mode_rows (kept_rows() x modes() row-major) and,
  // with a shift, its shift_products (the values the data had), needed
  // before the next extend.
  bool rows_given_away() const;
  void give_back_rows(std::vector<double>&& mode_rows, std::vector<double>&& shift_products);
  bool has_shift() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

}  // namespace pcsim::simulation
