#!/usr/bin/env bash
# Builds the cargo-fuzz targets and runs each for a bounded time; a crash (panic, abort, out of
# memory, timeout of one input) fails with the reproducer saved under fuzz/artifacts/<target>/.
#   bash fuzz/run.sh [SECONDS_PER_TARGET]   (default 20)
#
# Only the stable toolchain exists here. cargo-fuzz's instrumentation flags are stable codegen
# options (-Cpasses=sancov-module, -Cllvm-args=-sanitizer-coverage-*), but cargo-fuzz itself
# passes a few unstable ones; RUSTC_BOOTSTRAP=1 lets the stable compiler accept them. With
# `--sanitizer none` no AddressSanitizer runtime is needed (capmesh has no unsafe code outside
# the C ABI, which is not fuzzed here).
set -euo pipefail
cd "$(dirname "$0")"
seconds="${1:-20}"
export RUSTC_BOOTSTRAP=1
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked --version 0.13.1
cargo fuzz build --sanitizer none -O

# Seed corpora (gitignored): the tiny meshes in seeds/, converted to every format by capmesh.
capmesh="${CARGO_TARGET_DIR:-$PWD/../target}/release/capmesh"
[ -x "$capmesh" ] || (cd .. && cargo build --release --quiet)
rm -rf corpus && mkdir -p corpus/{read_obj,read_ply,read_off,read_stl,read_gifti,read_freesurfer,read_attributes,read_gzip,pipeline}
cp seeds/*.obj corpus/read_obj/
cp seeds/*.off corpus/read_off/
cp seeds/*.ply corpus/read_ply/
cp seeds/*.stl corpus/read_stl/
cp ../tests/data/neuro/nibabel_ascii.gii corpus/read_gifti/
for s in seeds/hexagon.obj seeds/octahedron.off; do
    base="$(basename "$s")"
    for ext in ply stl off obj; do
        # `param` writes the input's connectivity on the cap: binary PLY and STL, ASCII OFF/OBJ.
        "$capmesh" --quiet param "$s" -o "corpus/read_$ext/${base%.*}_cap.$ext" >/dev/null
    done
    # GIFTI (GZipBase64Binary) and FreeSurfer (`.pial`) surfaces.
    "$capmesh" --quiet param "$s" -o "corpus/read_gifti/${base%.*}_cap.gii" >/dev/null
    "$capmesh" --quiet param "$s" -o "corpus/read_freesurfer/${base%.*}_cap.pial" >/dev/null
done
# Attributes target: one format byte (0 GIFTI, 1 FreeSurfer curvature), then the file.
{ printf "\\x00"; cat seeds/labels.label.gii; } > corpus/read_attributes/labels
{ printf "\\x01"; cat seeds/three_values.curv; } > corpus/read_attributes/curv
# gzip target: one format byte, then a gzip stream.
i=0
for f in corpus/read_{obj,ply,off,stl,gifti,freesurfer}/*; do
    case "$f" in *read_obj*) k=0 ;; *read_ply*) k=1 ;; *read_off*) k=2 ;; *read_stl*) k=3 ;; *read_gifti*) k=4 ;; *) k=5 ;; esac
    { printf "\\x0$k"; gzip -c "$f"; } > "corpus/read_gzip/seed_$i"
    i=$((i + 1))
done
# pipeline target: a few byte strings that decode to each kind of mesh (see src/lib.rs).
for m in 0 1 2 3; do printf "\\x0$m\\x07\\x03\\x05\\x11\\x22\\x33\\x44\\x55" > "corpus/pipeline/mode_$m"; done

for t in read_obj read_ply read_off read_stl read_gifti read_freesurfer read_attributes read_gzip pipeline; do
    echo "== fuzz $t for ${seconds}s"
    # Inputs up to 4 KiB; one input may take at most 10 s and 2 GiB.
    cargo fuzz run --sanitizer none -O "$t" "corpus/$t" -- \
        -max_total_time="$seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 2>&1 \
        | grep -E "^(stat::number_of_executed_units|stat::new_units_added|#[0-9]+ +DONE)|panicked|ERROR|SUMMARY|Test unit written" || true
    if [ -n "$(ls -A "artifacts/$t" 2>/dev/null)" ]; then
        echo "fuzz target $t found a crash: fuzz/artifacts/$t/" >&2
        exit 1
    fi
done
