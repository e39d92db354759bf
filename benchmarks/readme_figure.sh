#!/usr/bin/env bash
# The README's picture (docs/img/face.png): builds capmesh, installs matplotlib into
# benchmarks/.venv, renders the bundled face, its cap map and its remesh.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --bin capmesh
if [ ! -x benchmarks/.venv/bin/python ]; then
  python3 -m venv benchmarks/.venv
fi
benchmarks/.venv/bin/pip install -q matplotlib==3.9.2
benchmarks/.venv/bin/python benchmarks/readme_figure.py
