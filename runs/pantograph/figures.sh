#!/bin/bash
# Regenerates the pantograph figures (thesis Figs. 2.13-2.22) and tables.
# usage: runs/pantograph/figures.sh [FIGURE ...]   (default: all)
#   FIGURE: modes calibrate step harmonic friction linear energy frf sweep
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
run() { "$PCSIM_BIN" pantograph "$R/$1.yaml" -o "$OUT/$1"; }
figs=("$@")
[ ${#figs[@]} -eq 0 ] && figs=(modes calibrate step harmonic friction linear energy frf sweep)
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
    *) echo "unknown figure '$fig'" >&2; exit 2 ;;
  esac
done
