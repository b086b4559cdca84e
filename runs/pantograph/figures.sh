#!/bin/bash
# Regenerates the pantograph figures (thesis Figs. 2.13-2.22) and tables, with the thesis
# comparison of the rigid, linearised and flexible-bar models (docs/pantograph.md).
# usage: runs/pantograph/figures.sh [FIGURE ...]   (default: all)
#   FIGURE: modes calibrate step harmonic friction linear energy frf sweep
#           compare-modes compare-step compare-harmonic compare-friction compare-linear
#           compare-frf
# Env: PCSIM_BIN (default build/pcsim), PYTHON (default /usr/bin/python3),
#      OUT (default out/pantograph), FIGDIR (default docs/pantograph).
# Run from the repository root.
set -euo pipefail
PCSIM_BIN=${PCSIM_BIN:-build/pcsim}
PYTHON=${PYTHON:-/usr/bin/python3}
OUT=${OUT:-out/pantograph}
FIGDIR=${FIGDIR:-docs/pantograph}
R=runs/pantograph
mkdir -p "$OUT" "$FIGDIR"
declare -A ran  # each scene runs once per invocation
run() {
  [ -n "${ran[$1]:-}" ] && return 0
  "$PCSIM_BIN" pantograph "$R/$1.yaml" -o "$OUT/$1" --overwrite
  ran[$1]=1
}
figs=("$@")
[ ${#figs[@]} -eq 0 ] && figs=(modes calibrate step harmonic friction linear energy frf sweep
  compare-modes compare-step compare-harmonic compare-friction compare-linear compare-frf)
TABLES=$FIGDIR/tables
mkdir -p "$TABLES"
# time FIGURE TITLE RUN[=LABEL] ... [-- OPTIONS]: pantograph_time.py on runs of this script.
time_plot() {
  local png=$1 title=$2 dirs=() labels=""
  shift 2
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do
    dirs+=("$OUT/${1%%=*}")
    labels="$labels${labels:+,}${1#*=}"
    shift
  done
  [ "${1:-}" = "--" ] && shift
  $PYTHON postproc/pantograph_time.py "${dirs[@]}" -o "$FIGDIR/$png" --labels "$labels" \
    --title "$title" "$@"
}
for fig in "${figs[@]}"; do
  case $fig in
    modes) run dsa380_modes; run en50318_modes ;;
    calibrate) run calibrate ;;
    step)  # Fig. 2.13
      run dsa380_step
      $PYTHON postproc/pantograph_time.py "$OUT/dsa380_step" -o "$FIGDIR/fig2_13_step.png" \
        --labels step --title "Step of the contact force to 120 N (Fig. 2.13)" ;;
    harmonic)  # Fig. 2.15
      run dsa380_harmonic
      $PYTHON postproc/pantograph_time.py "$OUT/dsa380_harmonic" -o "$FIGDIR/fig2_15_harmonic.png" \
        --labels harmonic --title "Contact force 120 + 30 sin(4πt) N (Fig. 2.15)" ;;
    friction)  # Figs. 2.16-2.17
      run dsa380_harmonic; run dsa380_friction
      $PYTHON postproc/pantograph_time.py "$OUT/dsa380_harmonic" "$OUT/dsa380_friction" \
        -o "$FIGDIR/fig2_16_friction.png" --labels "no friction,friction ±10 N" --schemes rk4 \
        --title "Friction ±10 N, kt = 5e-4 m/s vs none (Figs. 2.16-2.17)" ;;
    linear)  # Fig. 2.18
      run dsa380_linear_vs_nonlinear
      $PYTHON postproc/pantograph_time.py "$OUT/dsa380_linear_vs_nonlinear" -o "$FIGDIR/fig2_18_linear_vs_nonlinear.png" \
        --labels "" --title "Nonlinear vs linearised, amplitude 200 N (Fig. 2.18)" ;;
    energy)  # Energy balance (2.3.1)
      run dsa380_energy
      $PYTHON postproc/pantograph_energy.py "$OUT/dsa380_energy" -o "$FIGDIR/energy_balance.png" ;;
    frf)  # Figs. 2.20-2.22 (linear)
      run dsa380_frf; run dsa380_frf_restrained
      $PYTHON postproc/pantograph_frf.py "$OUT/dsa380_frf" "$OUT/dsa380_frf_restrained" -o "$FIGDIR/frf_h33.png" ;;
    sweep)  # nonlinear FRF (2.3.3)
      run dsa380_frf; run dsa380_frf_restrained; run dsa380_sweep_none; run dsa380_sweep_rotation
      $PYTHON postproc/pantograph_sweep.py "$OUT/dsa380_sweep_none" -o "$FIGDIR/sweep_unrestrained.png" --frf "$OUT/dsa380_frf"
      $PYTHON postproc/pantograph_sweep.py "$OUT/dsa380_sweep_rotation" -o "$FIGDIR/sweep_rotation_restrained.png" --frf "$OUT/dsa380_frf_restrained" ;;
    compare-modes)  # Table 2.2: rigid (linearised) vs flexible-bar modes
      run dsa380_modes; run flexible_modes
      $PYTHON postproc/pantograph_compare.py modes "$OUT/dsa380_modes" "$OUT/flexible_modes" \
        --markdown | tee "$TABLES/modes_rigid_flexible.md" ;;
    compare-step)  # Fig. 2.13, rigid vs flexible (HHT for the flexible bars)
      run dsa380_step; run flexible_step
      time_plot fig2_13_rigid_flexible.png "Step to 120 N, rigid vs flexible (Fig. 2.13)" \
        dsa380_step=rigid flexible_step=flexible ;;
    compare-harmonic)  # Fig. 2.15, rigid vs flexible
      run dsa380_harmonic; run flexible_harmonic
      time_plot fig2_15_rigid_flexible.png "120 + 30 sin(4πt) N, rigid vs flexible (Fig. 2.15)" \
        dsa380_harmonic=rigid flexible_harmonic=flexible -- --schemes rk4,hht ;;
    compare-friction)  # Figs. 2.16-2.17 (detail of the steady state), rigid and flexible
      run dsa380_harmonic; run dsa380_friction; run flexible_harmonic; run flexible_friction
      time_plot fig2_17_friction_rigid_flexible.png \
        "Friction ±10 N vs none, steady state (Fig. 2.17)" dsa380_harmonic="rigid" \
        dsa380_friction="rigid friction" flexible_harmonic="flexible" \
        flexible_friction="flexible friction" -- --schemes hht --xlim 8 10 ;;
    compare-linear)  # Fig. 2.18: nonlinear vs linearised, rigid and flexible
      run dsa380_linear_vs_nonlinear; run flexible_linear_vs_nonlinear
      time_plot fig2_18_rigid_flexible.png "Nonlinear vs linearised, 200 N at 1 Hz (Fig. 2.18)" \
        dsa380_linear_vs_nonlinear=rigid flexible_linear_vs_nonlinear=flexible ;;
    compare-frf)  # Fig. 2.22: the four models (rigid/flexible, linearised/nonlinear at 10 N)
      run dsa380_frf; run flexible_frf; run dsa380_sweep_fig222; run flexible_sweep
      $PYTHON postproc/pantograph_compare.py frf -o "$FIGDIR/fig2_22_four_models.png" \
        --rigid-frf "$OUT/dsa380_frf" --rigid-sweep "$OUT/dsa380_sweep_fig222" \
        --flexible-frf "$OUT/flexible_frf" --flexible-sweep "$OUT/flexible_sweep" |
        tee "$TABLES/fig2_22_peaks.txt" ;;
    *) echo "unknown figure '$fig'" >&2; exit 2 ;;
  esac
done
