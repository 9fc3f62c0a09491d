#!/usr/bin/env bash
# The peer match (doc/peer.md): bar1d --peer getfem-vK reproduces the displacement measures that GetFEM's
# demo_dynamic_contact_1D.py printed (tests/data/getfem/measures.dat, made once with python3-getfem; CI
# does not need it), each to the tolerance of its row; and so does a preset with a beta of its own
# (tests/data/getfem/measures_own_beta.dat: getfem-v1 with beta = 1/4, the start the demo takes).
# Usage: getfem_peer.sh BIN_DIR
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/tools/getfem_peer.sh" "$1/bar1d" "$root/tests/data/getfem/measures.dat"
bash "$root/tools/getfem_peer.sh" "$1/bar1d" "$root/tests/data/getfem/measures_own_beta.dat"
