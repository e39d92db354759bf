#!/usr/bin/env bash
# Builds the capmesh MeshLab plugin: meshlab-plugin/build/libfilter_capmesh.so.
#   1. system packages for compiling (Qt 5 headers and moc, Eigen, GLEW headers, CMake) —
#      installed with apt-get when missing (needs root, as on CI);
#   2. fetch_meshlab_sdk.sh: MeshLab 2025.07 headers (Debian source package) and the pymeshlab
#      wheel with libmeshlab-common.so, in meshlab-plugin/.venv;
#   3. capmesh as a static library with its C ABI: cargo build --release --no-default-features --features capi;
#   4. CMake.
# Environment: CARGO_TARGET_DIR (default <repo>/target), CARGO_BUILD_JOBS, BUILD_JOBS (make -j).
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
BUILD="$HERE/build"

packages=(cmake qtbase5-dev libqt5opengl5-dev libeigen3-dev libglew-dev dpkg-dev)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    echo "build.sh: installing ${missing[*]}"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

bash "$HERE/fetch_meshlab_sdk.sh"
PYMESHLAB_LIB="$("$HERE/.venv/bin/python" -c 'import os, pymeshlab; print(os.path.join(os.path.dirname(pymeshlab.__file__), "lib"))')"

TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
( cd "$ROOT" && cargo build --release --no-default-features --features capi --lib )
CAPMESH_LIB="$TARGET_DIR/release/libcapmesh.a"
[ -f "$CAPMESH_LIB" ] || { echo "build.sh: $CAPMESH_LIB was not built" >&2; exit 1; }

cmake -S "$HERE" -B "$BUILD/cmake" -DCMAKE_BUILD_TYPE=Release \
    -DMESHLAB_SOURCE_DIR="$BUILD/meshlab-src" \
    -DMESHLAB_LIB_DIR="$PYMESHLAB_LIB" \
    -DCAPMESH_INCLUDE_DIR="$ROOT/cpp/include" \
    -DCAPMESH_LIBRARY="$CAPMESH_LIB" >/dev/null
cmake --build "$BUILD/cmake" -j "${BUILD_JOBS:-2}"
cp "$BUILD/cmake/libfilter_capmesh.so" "$BUILD/libfilter_capmesh.so"
echo "build.sh: plugin at $BUILD/libfilter_capmesh.so"
