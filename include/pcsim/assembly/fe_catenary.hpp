// The finite-element catenary (thesis 3.1) as a CatenaryModel: ANCF cables,
// bars, point masses and springs of a CatenaryMesh on the METIS-distributed
// CatenarySystem. Its terms (catenary_terms.hpp):
//  - cable forces: full nonlinear ANCF (fidelity nonlinear: the scene's
//    catenary.model), else linearised about the static configuration, f ~ b0 + K0 (U - U0);
//  - bar forces (droppers, steady arms, stitch wires) with their slack
//    criteria when dropper slack is on;
//  - inertia M A and Rayleigh damping C = alpha M + beta K_static (eq. 3.1).
// The constant matrices share the Jacobian's pattern and are built once, at
// the static configuration.
#pragma once

#include <map>
#include <memory>
#include <vector>

#include "pcsim/assembly/catenary_model.hpp"
#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/contact/wire_locator.hpp"

namespace pcsim::assembly {

class FECatenary : public CatenaryModel {
 public:
  // Flag for static_tangent(): a separate matrix of the selected terms (every
  // constant matrix holds only its own entries, a subset of the Jacobian's
  // pattern; the flag keeps the bars' matrix apart from K0 of the same terms).
  static constexpr unsigned kOwnPattern = 0x100;

  // static_node_values: the static configuration (6 per node); fidelity:
  // nonlinear (full ANCF cable forces) or linear (cables linearised about
  // the static configuration). node_owner: a partition to reuse (see
  // DofLayout), or null.
  FECatenary(MPI_Comm comm, catenary::CatenaryMesh mesh, std::vector<double> static_node_values,
             PetscInt extra_dofs, catenary::CatenaryFidelity fidelity,
             const std::vector<int>* node_owner = nullptr);
  ~FECatenary() override;

  CatenarySystem& system() { return *system_; }
  const CatenarySystem& system() const { return *system_; }
  const std::vector<double>& static_node_values() const { return static_values_; }
  // Locator of contact wire k (0-based among the contact wires).
  const contact::ContactWireLocator& locator(int wire = 0) const { return *locators_[wire]; }

  // Constant matrices at the static configuration, with their own entries
  // only (a subset of the pattern given to make_terms; owned by the model,
  // built on first use).
  Mat mass_matrix();
  Mat static_tangent(unsigned system_terms);  // CatenarySystem::Terms mask
  Vec static_forces(unsigned system_terms);   // forces at the static configuration
  Vec reference_vector() const { return U0_; }

  MPI_Comm comm() const override { return system_->comm(); }
  const catenary::CatenaryMesh& mesh() const override { return system_->mesh(); }
  catenary::CatenaryFidelity fidelity() const override { return fidelity_; }
  PetscInt catenary_dofs() const override { return system_->layout().catenary_dofs(); }
  PetscInt extra_global(PetscInt k) const override { return system_->layout().extra_global(k); }
  Vec create_vector() const override { return system_->create_vector(); }
  Mat create_matrix(const std::vector<bool>& wire_coupled) const override;
  // J0 of the cheap path without the pantographs' couplings with the whole
  // contact wire: contact enters J0 only as rank-one terms (1000 spans, 2
  // ranks: a smaller J0, interior copy and factor; docs/scaling.md).
  bool has_reference_pattern() const override { return true; }
  Mat create_reference_matrix(const std::vector<bool>& wire_coupled) const override {
    return create_matrix(std::vector<bool>(wire_coupled.size(), false));
  }
  void reference_state(Vec U) const override;
  void load_state(Vec U) override { system_->load_state(U); }
  int contact_wire_count() const override { return static_cast<int>(locators_.size()); }
  const WirePoint& wire_point(double x, int wire) const override;
  double wire_slope(double x, int wire) const override;
  double wire_x_min(int wire) const override { return locators_[wire]->x_min(); }
  double wire_x_max(int wire) const override { return locators_[wire]->x_max(); }
  std::vector<double> support_heights() const override;
  std::vector<double> dropper_forces() const override;
  std::vector<double> node_positions_to_root(Vec U) const override {
    return system_->gather_positions_to_root(U);
  }
  std::vector<std::unique_ptr<Term>> make_terms(const contact::InteractionEffects& e,
                                                Mat pattern) override;

 private:
  std::unique_ptr<CatenarySystem> system_;
  std::vector<double> static_values_;
  catenary::CatenaryFidelity fidelity_;
  std::vector<std::unique_ptr<contact::ContactWireLocator>> locators_;
  mutable std::vector<WirePoint> points_;  // the last wire_point() of each wire
  std::vector<int> droppers_;              // dropper bars in mesh order (records)
  bool dropper_slack_ = true;              // the scene's effect (make_terms)
  Mat mass_ = nullptr;
  std::map<unsigned, Mat> tangents_;
  std::map<unsigned, Vec> forces_;
  Vec U0_ = nullptr;
};

}  // namespace pcsim::assembly
