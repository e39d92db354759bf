#!/usr/bin/env bash
# Stage times and peak memory of capmesh on the bundled and synthetic (10k, 100k, 1M vertex)
# meshes, with MeshLab's isotropic explicit remeshing timed on the same inputs in the same run.
#   bash benchmarks/stage_bench.sh [--sizes 10k,100k,1m] [--skip-meshlab] [--skip-shared] [--limit S]
#   bash benchmarks/stage_bench.sh --scale   # subdivided brains (50k-776k) and a 1M closed surface:
#                                            # benchmarks/results/stage_bench_scale.{md,json} (no MeshLab)
# Writes benchmarks/results/stage_bench.{md,json}. pymeshlab (pinned) goes into benchmarks/.venv.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --bin capmesh --example synth_mesh
skip=0
for a in "$@"; do { [ "$a" = "--skip-meshlab" ] || [ "$a" = "--scale" ]; } && skip=1; done
if [ "$skip" = 0 ]; then
  [ -x benchmarks/.venv/bin/python ] || python3 -m venv benchmarks/.venv
  benchmarks/.venv/bin/python -c "import pymeshlab" 2>/dev/null || benchmarks/.venv/bin/pip install -q pymeshlab==2025.7.post1
fi
python3 benchmarks/stage_bench.py "$@"
