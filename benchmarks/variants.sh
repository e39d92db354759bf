#!/usr/bin/env bash
# Remesh quality on re-triangulated and subdivided copies (MeshLab isotropic remeshing, quadric decimation, midpoint subdivision)
# of the bundled meshes: builds capmesh, installs pinned pymeshlab into benchmarks/.venv, runs
# benchmarks/variants.py (arguments passed on, e.g. --faces 20000, --meshes closed_bunny_npm).
# Writes benchmarks/results/variants.{md,json}.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --bin capmesh
[ -x benchmarks/.venv/bin/python ] || python3 -m venv benchmarks/.venv
benchmarks/.venv/bin/python -c "import pymeshlab" 2>/dev/null || benchmarks/.venv/bin/pip install -q pymeshlab==2025.7.post1
benchmarks/.venv/bin/python benchmarks/variants.py "$@"
