#!/usr/bin/env bash
# One command for the remeshing comparison: builds capmesh, installs pinned pymeshlab, pyacvd,
# gpytoolbox, pyinstantmeshes and matplotlib into benchmarks/.venv, runs
# benchmarks/meshlab_compare.py with the arguments given here (e.g. --quick, --methods
# capmesh,isotropic, --capmesh-args "--optimize area", --repeats 5; see its --help).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release
if [ ! -x benchmarks/.venv/bin/python ]; then
  python3 -m venv benchmarks/.venv
fi
benchmarks/.venv/bin/pip install -q pymeshlab==2025.7.post1 pyacvd==0.4.0 gpytoolbox==0.3.8 pyinstantmeshes==1.0.0 matplotlib==3.11.2
benchmarks/.venv/bin/python benchmarks/meshlab_compare.py "$@"
