#!/usr/bin/env bash
# One command for the MeshLab remeshing comparison: builds capmesh, installs pinned pymeshlab
# and matplotlib into benchmarks/.venv, runs benchmarks/meshlab_compare.py.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release
if [ ! -x benchmarks/.venv/bin/python ]; then
  python3 -m venv benchmarks/.venv
fi
benchmarks/.venv/bin/pip install -q pymeshlab==2025.7.post1 matplotlib==3.9.2
benchmarks/.venv/bin/python benchmarks/meshlab_compare.py
