#!/usr/bin/env python3
"""The README's picture: the bundled face, its adaptive cap map and its remesh.

Run through benchmarks/readme_figure.sh (builds capmesh, makes a venv with matplotlib and
writes docs/img/face.png).
"""

import gzip
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CAPMESH = os.path.join(ROOT, "target", "release", "capmesh")
INPUT = os.path.join(ROOT, "tests", "data", "open_face_choi.obj.gz")
OUT = os.path.join(ROOT, "docs", "img", "face.png")


def load_obj(path):
    opener = gzip.open if path.endswith(".gz") else open
    vertices, faces = [], []
    with opener(path, "rt") as f:
        for line in f:
            s = line.split()
            if not s:
                continue
            if s[0] == "v":
                vertices.append([float(x) for x in s[1:4]])
            elif s[0] == "f":
                faces.append([int(x.split("/")[0]) - 1 for x in s[1:4]])
    return np.array(vertices), np.array(faces)


def shade(v, f, light=(0.3, 0.4, 1.0)):
    n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    n /= np.linalg.norm(n, axis=1)[:, None] + 1e-300
    light = np.array(light) / np.linalg.norm(light)
    return 0.35 + 0.65 * np.abs(n @ light)


def panel(ax, v, f, title, edges=False, view=(90, -90)):
    g = shade(v, f)
    colors = np.stack([0.55 * g, 0.7 * g, 0.9 * g, np.ones_like(g)], axis=1)
    ax.add_collection3d(Poly3DCollection(v[f], facecolors=colors, edgecolors=(0, 0, 0, 0.5) if edges else "none", linewidths=0.15))
    lo, hi = v.min(0), v.max(0)
    mid, r = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(mid[0] - r, mid[0] + r)
    ax.set_ylim(mid[1] - r, mid[1] + r)
    ax.set_zlim(mid[2] - r, mid[2] + r)
    ax.view_init(*view)
    ax.set_axis_off()
    ax.set_title(title, fontsize=10)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        cap, remeshed = os.path.join(tmp, "cap.obj"), os.path.join(tmp, "remeshed.obj")
        subprocess.run([CAPMESH, "param", INPUT, "-o", cap, "--quiet"], check=True, stdout=subprocess.DEVNULL)
        subprocess.run([CAPMESH, "remesh", INPUT, "-o", remeshed, "--faces", "3000", "--quiet"], check=True, stdout=subprocess.DEVNULL)
        meshes = [load_obj(INPUT), load_obj(cap), load_obj(remeshed)]
    fig = plt.figure(figsize=(9, 3.2))
    titles = ["input (17k vertices)", "adaptive cap Z >= Z*", "remesh (3000 faces)"]
    for i, ((v, f), title) in enumerate(zip(meshes, titles)):
        ax = fig.add_subplot(1, 3, i + 1, projection="3d")
        panel(ax, v, f, title, edges=(i == 2), view=(90, -90) if i != 1 else (35, -60))
    plt.subplots_adjust(left=0, right=1, top=0.9, bottom=0, wspace=0)
    plt.savefig(OUT, dpi=90)
    print(f"wrote {OUT}", file=sys.stderr)


if __name__ == "__main__":
    main()
