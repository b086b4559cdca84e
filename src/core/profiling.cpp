#include "pcsim/core/profiling.hpp"

#include <map>
#include <string>

#include "pcsim/core/error.hpp"

namespace pcsim {

namespace {
PetscClassId pcsim_class_id() {
  static PetscClassId id = [] {
    PetscClassId c = 0;
    PCSIM_PETSC(PetscClassIdRegister("pcsim", &c));
    return c;
  }();
  return id;
}

PetscLogEvent register_event(const char* name) {
  PetscLogEvent e = 0;
  PCSIM_PETSC(PetscLogEventRegister(name, pcsim_class_id(), &e));
  return e;
}
}  // namespace

const LogEvents& log_events() {
  static const LogEvents events = [] {
    LogEvents e;
    e.residual = register_event("pcsimResidual");
    e.linear_parts = register_event("pcsimLinearParts");
    e.residual_update = register_event("pcsimResidualUpd");
    e.state_load = register_event("pcsimStateLoad");
    e.contact = register_event("pcsimContact");
    e.low_rank_change = register_event("pcsimLowRankChg");
    e.woodbury = register_event("pcsimWoodbury");
    e.record = register_event("pcsimRecord");
    e.dd_setup = register_event("pcsimDDSetUp");
    e.dd_apply = register_event("pcsimDDApply");
    e.dd_interface = register_event("pcsimDDInterface");
    e.shift_products = register_event("pcsimShiftProd");
    e.shift_gemm = register_event("pcsimShiftGemm");
    e.basis_assembly = register_event("pcsimBasisAsm");
    return e;
  }();
  return events;
}

void LogStage::next(const char* name) {
  if (pushed_) PCSIM_PETSC(PetscLogStagePop());
  pushed_ = false;
  static std::map<std::string, PetscLogStage> stages;
  auto it = stages.find(name);
  if (it == stages.end()) {
    PetscLogStage stage;
    PCSIM_PETSC(PetscLogStageRegister(name, &stage));
    it = stages.emplace(name, stage).first;
  }
  PCSIM_PETSC(PetscLogStagePush(it->second));
  pushed_ = true;
}

LogStage::~LogStage() {
  if (pushed_) PetscLogStagePop();
}

}  // namespace pcsim
