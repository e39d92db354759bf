#!/usr/bin/env bash
# Remesh quality on re-triangulated and subdivided copies (MeshLab isotropic remeshing, quadric decimation, midpoint subdivision, marching cubes of a voxel segmentation)
# of the bundled meshes: builds capmesh, installs pinned pymeshlab, gpytoolbox and scikit-image into benchmarks/.venv, runs
# benchmarks/variants.py (arguments passed on, e.g. --faces 20000, --meshes closed_bunny_npm).
# Writes benchmarks/results/variants.{md,json}.
set -euo pipefail
# gpytoolbox's C++ core refuses a C.UTF-8 locale it cannot build.
export LC_ALL=C
cd "$(dirname "$0")/.."
cargo build --release --bin capmesh
[ -x benchmarks/.venv/bin/python ] || python3 -m venv benchmarks/.venv
benchmarks/.venv/bin/pip install -q pymeshlab==2025.7.post1 gpytoolbox==0.3.8 scikit-image==0.26.0
benchmarks/.venv/bin/python benchmarks/variants.py "$@"
