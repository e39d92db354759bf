#!/usr/bin/env bash
# docs/img/scha_face.png: builds capmesh, installs matplotlib into benchmarks/.venv, renders the
# face and its order-15 reconstructions in both harmonic bases.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --bin capmesh
if [ ! -x benchmarks/.venv/bin/python ]; then
  python3 -m venv benchmarks/.venv
fi
benchmarks/.venv/bin/pip install -q matplotlib==3.9.2
benchmarks/.venv/bin/python benchmarks/scha_figure.py
