#!/usr/bin/env bash
# Remesh quality on anatomical meshes that are not in the repository (FreeSurfer's fsaverage5 surfaces,
# the Conte69 32k surfaces and its open cortex, the MNI152 brain and head segmented, synthetic long bones, pymeshlab's sample bone): builds capmesh, installs pymeshlab (benchmarks/variants.py's bars are shared)
# into benchmarks/.venv, downloads nilearn's and BrainSpace's wheels for their bundled surfaces, runs benchmarks/external.py
# (arguments passed on, e.g. --faces 5000). Writes benchmarks/results/external.{md,json}.
set -euo pipefail
export LC_ALL=C
cd "$(dirname "$0")/.."
cargo build --release --bin capmesh
[ -x benchmarks/.venv/bin/python ] || python3 -m venv benchmarks/.venv
benchmarks/.venv/bin/pip install -q pymeshlab==2025.7.post1 gpytoolbox==0.3.8 scikit-image==0.26.0 nibabel==5.4.2
benchmarks/.venv/bin/python benchmarks/external.py "$@"
