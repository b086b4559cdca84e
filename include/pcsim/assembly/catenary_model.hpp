// A catenary model behind the coupled system: it owns the catenary part of
// the state vector and contributes the catenary's terms. The finite-element
// model (FECatenary: nonlinear ANCF or cables linearised about the static
// configuration) is one; a reduced-order (modal) model is another behind the
// same interface. The contact terms see the catenary only through
// wire_point(x, wire): the height of contact wire 'wire' at station x as a
// linear function of the catenary's unknowns. A line with overlaps between
// tension sections has several contact wires (contact_wire_count(), each
// over its station range); a pantograph has one contact term per wire.
//
// The global vector holds the catenary's unknowns followed by 'extra'
// unknowns (the pantographs' coordinates), which the last rank owns.
#pragma once

#include <petscmat.h>
#include <petscvec.h>

#include <functional>
#include <memory>
#include <vector>

#include "pcsim/assembly/term.hpp"
#include "pcsim/catenary/mesh.hpp"
#include "pcsim/catenary/reduced_basis.hpp"
#include "pcsim/contact/pantograph_run.hpp"

namespace pcsim::assembly {

// A contact wire at station x: z(U) = z0 + sum_i weight_i (U[index_i] - U_ref[index_i])
// near the current state, i.e. weight = dz/dU (chi fixed, thesis 3.9-3.13).
struct WirePoint {
  bool on_wire = false;  // x lies on the contact wire
  bool owned = false;    // this rank holds the state of the point: z is set
  double z = 0;          // height the contact sees at x at the loaded state [m]
                         // (the wire + its contact-gap offset, mesh.hpp)
  double y = 0;          // lateral position at x from the track centre line [m] at the loaded state
                         // (modal in still air: the static one, its basis keeps no lateral rows)
  std::vector<PetscInt> index;  // global unknowns z depends on (every rank)
  std::vector<double> weight;   // dz/dU for those unknowns (every rank)
  // Static compliance at x that the unknowns leave out (a reduced model's
  // truncated modes) [m/N]: a spring in series with the contact. 0 for FE.
  double residual_flexibility = 0;
  double residual_flexibility_slope = 0;  // its d/dx [m/N per m]
  // The same few unknowns recur as x moves (FE: the element's DOFs), so that
  // a solver may cache a solve per unknown; false for dense weights (modes).
  bool reuse_columns = true;
  // index is index[0], index[0] + 1, ... (dense weights over a block).
  bool contiguous = false;
};

class CatenaryModel {
 public:
  virtual ~CatenaryModel() = default;
  virtual MPI_Comm comm() const = 0;
  virtual const catenary::CatenaryMesh& mesh() const = 0;
  // The fidelity level the model is (the scene's catenary.model): its terms
  // follow from it.
  virtual catenary::CatenaryFidelity fidelity() const = 0;

  // Unknowns: the catenary's, then the extras (owned by the last rank).
  virtual PetscInt catenary_dofs() const = 0;
  virtual PetscInt extra_global(PetscInt k) const = 0;
  virtual Vec create_vector() const = 0;
  // The pattern of every term the model contributes, the extras coupled
  // densely with each other, and each extra marked in wire_coupled coupled
  // with every unknown a wire point may involve: zeros inserted, not yet
  // assembled (the caller adds the other terms' patterns).
  virtual Mat create_matrix(const std::vector<bool>& wire_coupled) const = 0;
  // The pattern of the reference tangents only (the cheap path's J0), when it
  // is smaller: without the couplings only the exact tangents of low-rank
  // terms touch (a modal model's contact and slack droppers couple every mode).
  virtual bool has_reference_pattern() const { return false; }
  virtual Mat create_reference_matrix(const std::vector<bool>& wire_coupled) const {
    return create_matrix(wire_coupled);
  }

  // The static configuration (the linearisation point), catenary part.
  virtual void reference_state(Vec U) const = 0;
  // Makes the state U current for the queries below (collective).
  virtual void load_state(Vec U) = 0;
  // Contact wires 0..contact_wire_count()-1 (mesh().contact_wire_list()
  // order): the point at station x and each wire's station range. The point
  // is the model's own (no copy of its weights): valid until the next
  // wire_point() of the same wire or the next load_state().
  virtual int contact_wire_count() const = 0;
  virtual const WirePoint& wire_point(double x, int wire) const = 0;
  // dz/dx of the wire at x at the loaded state, on the rank whose point is
  // owned (else 0): the moving contact's power alone needs it (energy
  // balance), so a point does not carry it.
  virtual double wire_slope(double x, int wire) const = 0;
  virtual double wire_x_min(int wire) const = 0;
  virtual double wire_x_max(int wire) const = 0;
  // The catenary part of U in static equilibrium under upward forces, each
  // at station x on contact wire 'wire', when the model has it in closed form
  // (a modal model, slack ignored: the loads superposed); false otherwise (the
  // caller solves for it).
  struct PointForce {
    double x = 0;
    int wire = 0;
    double force = 0;
  };
  virtual bool closed_form_point_loads(const std::vector<PointForce>& loads, Vec U) const {
    return false;
  }
  // Contact-wire height at every support and axial force of every dropper at
  // the loaded state: set by the ranks that own them, zero elsewhere (the
  // caller sums over ranks).
  virtual std::vector<double> support_heights() const = 0;
  virtual std::vector<double> dropper_forces() const = 0;
  // The same in batches, for a model that pays a product per state for them
  // (the reduced catenary): keep_record_state() keeps the loaded state, and
  // take_kept_records() hands the kept states over (the next one starts a new
  // batch) with the computation of their support heights and (if asked)
  // dropper forces, state after state, in one product. The computation reads
  // the states it holds and the model's constant data only: it may run on
  // another thread while the model steps on (RunSession). Set on the owning
  // ranks, zero elsewhere.
  struct RecordQuantities {
    std::size_t states = 0;
    std::vector<double> support_z;      // states x support_heights().size()
    std::vector<double> dropper_force;  // states x dropper_forces().size(), or empty
  };
  virtual bool batches_records() const { return false; }
  // Whether batches cost less than records one at a time (which also anchor
  // the next step's checks, as a batch does not). Collective.
  virtual bool records_batch_pays() const { return false; }
  virtual void keep_record_state() {}
  virtual std::function<RecordQuantities()> take_kept_records(bool dropper_forces) {
    return [] { return RecordQuantities{}; };
  }

  // Node positions (3 per node) of state U on rank 0, empty elsewhere
  // (field snapshots; collective).
  virtual std::vector<double> node_positions_to_root(Vec U) const = 0;

  // The catenary's terms at its fidelity for these effects: forces,
  // inertia, damping, bars.
  // Their constant matrices are duplicated from 'pattern' (the Jacobian's
  // final pattern, assembled; the model keeps a reference).
  virtual std::vector<std::unique_ptr<Term>> make_terms(const contact::InteractionEffects& e,
                                                        Mat pattern) = 0;
};

}  // namespace pcsim::assembly
