#!/usr/bin/env python3
"""docs/img/scha_face.png: the bundled face and its order-15 reconstructions with the paper's
adaptive harmonics (the boundary loop pinched to a point) and with spherical cap harmonics
(Neumann; the loop kept), each resampled on a cap grid of 6000 faces, boundary in red.

Run through benchmarks/scha_figure.sh (builds capmesh, makes a venv with matplotlib).
"""

import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from readme_figure import CAPMESH, INPUT, ROOT, load_obj, panel  # noqa: E402

OUT = os.path.join(ROOT, "docs", "img", "scha_face.png")


def boundary_edges(f):
    count = {}
    for a, b, c in f:
        for e in ((a, b), (b, c), (c, a)):
            k = (min(e), max(e))
            count[k] = count.get(k, 0) + 1
    return [k for k, n in count.items() if n == 1]


def main():
    meshes = [load_obj(INPUT)]
    with tempfile.TemporaryDirectory() as tmp:
        for basis in ("ah", "scha"):
            out = os.path.join(tmp, f"{basis}.obj")
            subprocess.run([CAPMESH, "harmonics", INPUT, "--order", "15", "--basis", basis, "--resample-faces", "6000",
                            "-o", out, "--quiet"], check=True, stdout=subprocess.DEVNULL)
            meshes.append(load_obj(out))
    titles = ["input (17k vertices)", "adaptive harmonics, N = 15", "cap harmonics (Neumann), N = 15"]
    fig = plt.figure(figsize=(9, 3.2))
    for i, ((v, f), title) in enumerate(zip(meshes, titles)):
        ax = fig.add_subplot(1, 3, i + 1, projection="3d")
        panel(ax, v, f, title)
        for a, b in boundary_edges(f):
            ax.plot(*np.stack([v[a], v[b]]).T, color="red", linewidth=1.2)
    plt.subplots_adjust(left=0, right=1, top=0.9, bottom=0, wspace=0)
    plt.savefig(OUT, dpi=90)
    print(f"wrote {OUT}", file=sys.stderr)


if __name__ == "__main__":
    main()
