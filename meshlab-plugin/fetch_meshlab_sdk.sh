#!/usr/bin/env bash
# Fetches what the plugin is compiled against, into meshlab-plugin/build/ (gitignored):
#   * MeshLab's headers: Debian source package `meshlab` 2025.07~dfsg from the unstable suite's
#     deb-src. The mirror is read from this machine's own apt sources; no host is written here.
#     Only a deb-src entry is added, so nothing from unstable is ever installed as a binary.
#   * libmeshlab-common.so and the Qt 5.15 libraries it was built with: the pymeshlab==2025.7.post1
#     wheel, installed into meshlab-plugin/.venv (also used by the tests).
# Needs root for apt-get. Idempotent: a finished step is not repeated.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
BUILD="$HERE/build"
SRC_VERSION="2025.07~dfsg"
PYMESHLAB_VERSION="2025.7.post1"
mkdir -p "$BUILD"

# ---- the Debian mirror, as configured on this machine ------------------------------------------
mirror_uri() {
    local f uri
    # deb822 sources: the first URI of a stanza that is not a security archive.
    for f in /etc/apt/sources.list.d/*.sources; do
        [ -f "$f" ] || continue
        uri=$(awk '/^URIs:/ { for (i = 2; i <= NF; i++) if ($i !~ /security/) { print $i; exit } }' "$f")
        if [ -n "$uri" ]; then echo "$uri"; return; fi
    done
    # one-line sources
    for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
        [ -f "$f" ] || continue
        uri=$(awk '$1 == "deb" { for (i = 2; i <= NF; i++) if ($i ~ /:\/\//) { if ($i !~ /security/) { print $i; exit } else break } }' "$f")
        if [ -n "$uri" ]; then echo "$uri"; return; fi
    done
    echo "fetch_meshlab_sdk.sh: no Debian mirror found in this machine's apt sources" >&2
    return 1
}

# ---- MeshLab's source ---------------------------------------------------------------------------
MESHLAB_DIR="$BUILD/meshlab-src"
if [ ! -f "$MESHLAB_DIR/src/common/plugins/interfaces/filter_plugin.h" ]; then
    MIRROR="$(mirror_uri)"
    LIST=/etc/apt/sources.list.d/capmesh-meshlab-unstable-src.sources
    cat > "$LIST" <<SRC
Types: deb-src
URIs: $MIRROR
Suites: unstable
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
    apt-get update -qq
    command -v dpkg-source >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y -qq dpkg-dev
    rm -rf "$BUILD/apt-src" && mkdir -p "$BUILD/apt-src"
    # the newest Debian revision of the pinned upstream version (e.g. 2025.07~dfsg-4)
    version=$(apt-cache showsrc meshlab | awk -v v="$SRC_VERSION" '/^Version:/ && index($2, v "-") == 1 { print $2 }' | sort -V | tail -n1)
    [ -n "$version" ] || { echo "fetch_meshlab_sdk.sh: meshlab $SRC_VERSION not in the unstable deb-src index" >&2; exit 1; }
    # Only the upstream tarball is needed (the headers and vcglib are in it). The mirror may not
    # carry the .dsc / Debian diff of every revision, so download what it has and check the
    # tarball against the SHA-256 in the signed source index.
    echo "fetch_meshlab_sdk.sh: downloading meshlab $version (a 404 for its .dsc or .debian.tar.xz is harmless)"
    ( cd "$BUILD/apt-src" && apt-get source -qq --download-only "meshlab=$version" ) || true
    orig="meshlab_$SRC_VERSION.orig.tar.xz"
    want=$(apt-cache showsrc meshlab | awk -v f="$orig" -v v="$version" '
        /^Version:/ { ver = $2 } /^Checksums-Sha256:/ { on = 1; next } /^[^ ]/ { on = 0 }
        on && ver == v && $3 == f { print $1; exit }')
    [ -f "$BUILD/apt-src/$orig" ] || { echo "fetch_meshlab_sdk.sh: $orig was not downloaded" >&2; exit 1; }
    have=$(sha256sum "$BUILD/apt-src/$orig" | cut -d' ' -f1)
    [ -n "$want" ] && [ "$want" = "$have" ] || { echo "fetch_meshlab_sdk.sh: $orig checksum $have, index says '$want'" >&2; exit 1; }
    rm -rf "$MESHLAB_DIR" && mkdir -p "$MESHLAB_DIR"
    tar -xJf "$BUILD/apt-src/$orig" -C "$MESHLAB_DIR" --strip-components=1
fi
echo "MeshLab source: $MESHLAB_DIR"

# ---- pymeshlab wheel (libmeshlab-common.so, bundled Qt) -----------------------------------------
VENV="$HERE/.venv"
if [ ! -x "$VENV/bin/python" ]; then
    python3 -m venv "$VENV"
fi
if ! "$VENV/bin/python" -c "import pymeshlab" 2>/dev/null; then
    "$VENV/bin/pip" install -q "pymeshlab==$PYMESHLAB_VERSION" pytest numpy
fi
"$VENV/bin/python" -c "import pymeshlab, os; print('pymeshlab lib:', os.path.join(os.path.dirname(pymeshlab.__file__), 'lib'))"
