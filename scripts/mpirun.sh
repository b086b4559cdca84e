#!/usr/bin/env bash
# mpirun as root with oversubscription allowed (CI machines have 2 cores).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
exec mpirun --oversubscribe "$@"
