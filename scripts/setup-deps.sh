#!/usr/bin/env bash
# Installs pcsim's build and run dependencies from Debian packages (idempotent).
# Usage: scripts/setup-deps.sh   (run as root, or with sudo available)
set -euo pipefail
PACKAGES=(build-essential cmake pkg-config
  petsc-dev slepc-dev libmetis-dev libhdf5-openmpi-dev libopenmpi-dev openmpi-bin
  libeigen3-dev libyaml-cpp-dev nlohmann-json3-dev libgtest-dev libssl-dev
  python3-numpy python3-h5py python3-matplotlib python3-scipy python3-pil time
  python3-paraview xvfb
  python3-dev pybind11-dev python3-mpi4py
  libblis4-serial libsuitesparse-dev)  # python3-paraview: ParaView's XDMF3 reader for
# tests/output; xvfb: a virtual X display for its renders there (ParaView's
# OpenGL needs one); python3-pil: the GIF writer of postproc/animate.py;
# libblis4-serial: an optimised BLAS behind Debian's libblas.so.3, for PETSc,
# SLEPc, MUMPS and the modal window's shift products (a dgemm of their
# blocks: 3.0 GFlop/s with the reference BLAS, 38 with BLIS; docs/benchmarks.md;
# serial: one thread per MPI rank; on a processor BLIS does not know, pcsim
# picks BLIS's vector kernels itself: src/core/blas_kernels.cpp);
# libsuitesparse-dev (also a dependency of petsc-dev): KLU, the sparse LU of
# the cheap path's varying blocks
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "pcsim setup: installing ${missing[*]}" >&2
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
