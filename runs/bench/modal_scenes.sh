# shellcheck shell=bash
# The modal scenes of runs/bench_modal_step.sh and runs/profile_modal_step.sh,
# by name (sourced: sets the associative array MODAL_SCENES).
# shellcheck disable=SC2034
declare -A MODAL_SCENES=(
  [en300]="runs/en50318-300-modal.yaml"
  [win70]="runs/interaction/two-pantographs-300-window.yaml --set catenary.model=modal"
  [win109]="runs/interaction/two-pantographs-300-window.yaml --set catenary.model=modal --set catenary.max_frequency_hz=108.8"
  [win136]="runs/interaction/two-pantographs-300-window.yaml --set catenary.model=modal --set catenary.max_frequency_hz=136.1"
  [two20]="runs/interaction/two-pantographs-300.yaml --set catenary.model=modal"
  [three]="runs/interaction/three-pantographs-300.yaml --set catenary.model=modal"
  [three109]="runs/interaction/three-pantographs-300.yaml --set catenary.model=modal --set catenary.max_frequency_hz=108.8"
  [two109]="runs/interaction/two-pantographs-300.yaml --set catenary.model=modal --set catenary.max_frequency_hz=108.8"
  [dsa136]="runs/interaction/dsa380-300-base.yaml --set catenary.model=modal --set catenary.max_frequency_hz=136.1"
  [ts300]="runs/lines/three-sections-300.yaml --set catenary.model=modal"
  [ts1]="runs/bench/one-section-300.yaml --set catenary.model=modal"
  [flex136]="runs/interaction/dsa380-300-flexible.yaml --set catenary.model=modal --set catenary.max_frequency_hz=136.1"
)
