#!/usr/bin/env bash
# The Python package against the CLI: overhead of `capmesh.remesh` on the 48k brain and cohort
# throughput of `capmesh.cohort.shape` on a local Dask cluster of 1 and 2 workers.
#   bash benchmarks/python_bench.sh [--runs N] [--copies K]
# Writes benchmarks/results/python.md. The package (with its `cohort` extra: pandas, Dask) is
# installed into $CARGO_TARGET_DIR/python-bench-venv, built in $CARGO_TARGET_DIR/python-bench-build.
set -euo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-$PWD/target}"
cargo build --release --bin capmesh
[ -x "$target/python-bench-venv/bin/python" ] || python3 -m venv "$target/python-bench-venv"
# The extension is built in a target directory of its own: built in the main one, its copy of
# the capmesh library (no default features) once left a stale library behind that a later
# `cargo build --release` of the binary linked against (`capmesh::figures` not found).
CARGO_TARGET_DIR="$target/python-bench-build" "$target/python-bench-venv/bin/pip" install -q --disable-pip-version-check "./python[cohort]"
CARGO_TARGET_DIR="$target" "$target/python-bench-venv/bin/python" benchmarks/python_bench.py "$@"
