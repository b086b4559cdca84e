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

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/catenary/reduced_basis.hpp"

namespace pcsim::simulation {

// 'x': the static configuration of 'system' (no extra unknowns). Collective;
// the result on every rank.
// progress(done, total): the modes computed so far, after each chunk of the
// interval (not for 'every mode'). shift: a moving window's shift S (global
// DOFs of 'system', S(g, h) = 1 where DOF g takes DOF h's displacement), or
// null; with it the data's shift_products (keeps every vector until the end:
// n x (modes + shapes) doubles).
using ModalProgress = std::function<void(long done, long total)>;
catenary::ModalData compute_modal_data(assembly::CatenarySystem& system, Vec x,
                                       double max_frequency_hz, bool full_shapes,
                                       const ModalProgress& progress = nullptr,
                                       Mat shift = nullptr);

}  // namespace pcsim::simulation
