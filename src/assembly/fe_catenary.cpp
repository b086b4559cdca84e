#include "pcsim/assembly/fe_catenary.hpp"

#include <algorithm>

#include "pcsim/assembly/catenary_terms.hpp"
#include "pcsim/assembly/wind_terms.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/contact/contact_kernel.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

using catenary::BarKind;

FECatenary::FECatenary(MPI_Comm comm, catenary::CatenaryMesh mesh,
                       std::vector<double> static_node_values, PetscInt extra_dofs,
                       catenary::CatenaryFidelity fidelity, const std::vector<int>* node_owner)
    : static_values_(std::move(static_node_values)), fidelity_(fidelity) {
  if (fidelity_ == catenary::CatenaryFidelity::modal)
    throw SolverError("FE catenary: the modal level is the modal catenary's, not the FE one's");
  system_ = std::make_unique<CatenarySystem>(comm, std::move(mesh), extra_dofs, node_owner);
  const auto& m = system_->mesh();
  const auto wires = m.contact_wire_list();
  if (wires.empty()) throw InputError(m.source_file, "wires", "the design has no contact wire");
  for (int w : wires)
    locators_.push_back(std::make_unique<contact::ContactWireLocator>(m, static_values_, w));
  points_.resize(locators_.size());
  const auto& bars = system_->mesh().bars;
  for (std::size_t b = 0; b < bars.size(); ++b)
    if (bars[b].kind == BarKind::dropper) droppers_.push_back(static_cast<int>(b));
  U0_ = system_->create_vector();
  reference_state(U0_);
}

FECatenary::~FECatenary() {
  MatDestroy(&mass_);
  for (auto& [mask, K] : tangents_) MatDestroy(&K);
  for (auto& [mask, b] : forces_) VecDestroy(&b);
  VecDestroy(&U0_);
}

void FECatenary::reference_state(Vec U) const {
  const auto& L = system_->layout();
  PCSIM_PETSC(VecSet(U, 0.0));
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(U, &a));
  for (int n : L.owned_nodes())
    for (int c = 0; c < 6; ++c) {
      const PetscInt g = L.global_dof(n, c);
      if (g >= 0) a[g - L.first_owned()] = static_values_[6 * n + c];
    }
  PCSIM_PETSC(VecRestoreArray(U, &a));
}

// Element couplings, the extras' dense block and, for the wire-coupled
// extras, every DOF of every contact-wire node (the contact point moves along
// the wires: the pattern never changes during a run).
Mat FECatenary::create_matrix(const std::vector<bool>& wire_coupled) const {
  const auto& L = system_->layout();
  std::vector<int> contact_nodes;
  for (int w : mesh().contact_wire_list())
    contact_nodes.insert(contact_nodes.end(), mesh().wires[w].nodes.begin(),
                         mesh().wires[w].nodes.end());
  std::vector<std::vector<int>> couplings(L.extra_dofs());
  for (std::size_t k = 0; k < wire_coupled.size(); ++k)
    if (wire_coupled[k]) couplings[k] = contact_nodes;
  Mat A = L.create_matrix(couplings, true);
  system_->insert_element_pattern(A);
  for (std::size_t k = 0; k < wire_coupled.size(); ++k) {
    if (!wire_coupled[k]) continue;
    const PetscInt extra = L.extra_global(static_cast<PetscInt>(k));
    for (int n : contact_nodes) {
      if (L.owner(n) != L.rank()) continue;
      for (int c = 0; c < 6; ++c) {
        const PetscInt g = L.global_dof(n, c);
        if (g < 0) continue;
        PCSIM_PETSC(MatSetValue(A, g, extra, 0.0, ADD_VALUES));
        PCSIM_PETSC(MatSetValue(A, extra, g, 0.0, ADD_VALUES));
      }
    }
  }
  return A;  // not assembled: the caller adds the other terms' entries
}

// The constant matrices hold only their own entries (a subset of the
// Jacobian's pattern): the Jacobian's pattern couples every pantograph with the
// whole contact wire, which in a product would send every contact-wire value
// to the pantographs' rank (docs/scaling.md).
Mat FECatenary::mass_matrix() {
  if (mass_) return mass_;
  mass_ = system_->layout().create_matrix();
  system_->assemble_mass(mass_);
  return mass_;
}

Mat FECatenary::static_tangent(unsigned mask) {
  auto it = tangents_.find(mask);
  if (it != tangents_.end()) return it->second;
  Mat K = system_->layout().create_matrix();
  // The bars' own matrix has rows only at the bars' nodes: without inodes
  // PETSc keeps its nonempty rows apart (compressed rows) and a product skips
  // the others.
  if ((mask & kOwnPattern) && !(mask & CatenarySystem::kCables))
    PCSIM_PETSC(MatSetOption(K, MAT_USE_INODES, PETSC_FALSE));
  system_->load_state(U0_);
  system_->add_forces(nullptr, K, mask & (CatenarySystem::kAllTerms | CatenarySystem::kTautBars));
  PCSIM_PETSC(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  tangents_[mask] = K;
  return K;
}

Vec FECatenary::static_forces(unsigned mask) {
  auto it = forces_.find(mask);
  if (it != forces_.end()) return it->second;
  Vec b = system_->create_vector();
  system_->load_state(U0_);
  system_->assemble_static(b, nullptr, mask);
  forces_[mask] = b;
  return b;
}

const WirePoint& FECatenary::wire_point(double x, int wire) const {
  WirePoint& point = points_[wire];
  point.on_wire = point.owned = false;
  point.z = point.y = 0;
  point.index.clear();
  point.weight.clear();
  int element;
  double chi;
  point.on_wire = locators_[wire]->locate(x, element, chi);
  if (!point.on_wire) return point;
  const auto& el = mesh().cables[element];
  const contact::Vector12d S = contact::shape_row(chi, el.ref_length, 2);
  PetscInt idx[12];
  system_->cable_indices(element, idx);
  for (int i = 0; i < 12; ++i)
    if (idx[i] >= 0 && S[i] != 0.0) {
      point.index.push_back(idx[i]);
      point.weight.push_back(S[i]);
    }
  const auto& L = system_->layout();
  if (L.owner(el.nodes[0]) == L.rank()) {
    catenary::Vec12 q;
    system_->cable_values(element, q.data());
    point.owned = true;
    point.z = S.dot(q);
    point.y = catenary::cable_point(el.ref_length, q, chi).r[1];
    if (!mesh().contact_gap_offsets.empty()) point.z += mesh().contact_gap_offsets[wire].at(x);
  }
  return point;
}

double FECatenary::wire_slope(double x, int wire) const {
  int element;
  double chi;
  if (!locators_[wire]->locate(x, element, chi)) return 0;
  const auto& el = mesh().cables[element];
  const auto& L = system_->layout();
  if (L.owner(el.nodes[0]) != L.rank()) return 0;
  catenary::Vec12 q;
  system_->cable_values(element, q.data());
  const catenary::CablePoint at = catenary::cable_point(el.ref_length, q, chi);
  double slope = at.r_chi[2] / at.r_chi[0];
  if (!mesh().contact_gap_offsets.empty()) slope += mesh().contact_gap_offsets[wire].slope_at(x);
  return slope;
}

std::vector<double> FECatenary::support_heights() const {
  const auto& L = system_->layout();
  const auto& supports = mesh().support_nodes;
  std::vector<double> z(supports.size(), 0.0);
  for (std::size_t s = 0; s < supports.size(); ++s)
    if (L.owner(supports[s]) == L.rank()) z[s] = system_->node_values(supports[s])[2];
  return z;
}

std::vector<double> FECatenary::dropper_forces() const {
  const auto& L = system_->layout();
  std::vector<double> forces(droppers_.size(), 0.0);
  for (std::size_t d = 0; d < droppers_.size(); ++d)
    if (L.owner(mesh().bars[droppers_[d]].nodes[0]) == L.rank())
      forces[d] = system_->bar_force(droppers_[d], dropper_slack_);
  return forces;
}

std::vector<std::unique_ptr<Term>> FECatenary::make_terms(const contact::InteractionEffects& e,
                                                          Mat /*pattern*/) {
  dropper_slack_ = e.dropper_slack;
  std::vector<std::unique_ptr<Term>> terms;
  if (fidelity_ == catenary::CatenaryFidelity::nonlinear)
    terms.push_back(std::make_unique<NonlinearCableForces>(*this));
  else
    terms.push_back(std::make_unique<LinearisedCableForces>(*this));
  terms.push_back(std::make_unique<BarForces>(*this, e.dropper_slack));
  terms.push_back(std::make_unique<Inertia>(*this));
  if (e.rayleigh_damping) terms.push_back(std::make_unique<RayleighDamping>(*this, e));
  if (!mesh().dashpots.empty()) terms.push_back(std::make_unique<NodeDashpots>(*this));
  if (!mesh().pins.empty()) terms.push_back(std::make_unique<NodePins>(*this));
  if (mesh().conditions.wind.any()) terms.push_back(std::make_unique<AerodynamicDamping>(*this));
  if (mesh().conditions.wind.any() && mesh().conditions.wind.turbulence.on)
    terms.push_back(std::make_unique<WindTurbulence>(*this));
  return terms;
}

}  // namespace pcsim::assembly
