#!/usr/bin/env python3
"""Self-intersecting faces: `capmesh metrics` against MeshLab's selection.

For each mesh of tests/data: the input, capmesh's remesh at 5000 faces, MeshLab's isotropic
explicit remeshing of it, and the input with its vertices jittered (many intersections of
every kind), each counted by pymeshlab's `compute_selection_by_self_intersections_per_face`
and by `capmesh metrics` (field `self_intersecting_faces`). Prints a markdown table.
Run with the benchmark venv: benchmarks/.venv/bin/python benchmarks/self_intersection_check.py
[mesh names...].
"""

import gzip
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import pymeshlab as ml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data")
CAPMESH = os.path.join(ROOT, "target", "release", "capmesh")
MESHES = sorted(f[: -len(".obj.gz")] for f in os.listdir(DATA) if f.endswith(".obj.gz") and not f.startswith("bad_"))


def meshlab_count(path):
    ms = ml.MeshSet()
    ms.load_new_mesh(path)
    ms.compute_selection_by_self_intersections_per_face()
    return ms.current_mesh().selected_face_number()


def capmesh_count(original, path):
    out = subprocess.run([CAPMESH, "metrics", original, path, "--json"], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)["self_intersecting_faces"]


def main():
    names = sys.argv[1:] or MESHES
    work = tempfile.mkdtemp(prefix="capmesh-selfx-")
    print("| mesh | variant | faces | MeshLab | capmesh |")
    print("|---|---|---:|---:|---:|")
    agree = total = 0
    for name in names:
        obj = os.path.join(work, name + ".obj")
        with gzip.open(os.path.join(DATA, name + ".obj.gz"), "rb") as src, open(obj, "wb") as dst:
            dst.write(src.read())
        variants = {"input": obj}
        cap = os.path.join(work, name + ".capmesh.obj")
        if subprocess.run([CAPMESH, "remesh", "--quiet", obj, "-o", cap, "--faces", "5000"], capture_output=True).returncode == 0:
            variants["capmesh remesh"] = cap
        ms = ml.MeshSet()
        ms.load_new_mesh(obj)
        ms.meshing_isotropic_explicit_remeshing(targetlen=ml.PercentageValue(1.0), iterations=10)
        iso = os.path.join(work, name + ".iso.ply")
        ms.save_current_mesh(iso, save_vertex_quality=False, save_vertex_color=False)
        variants["MeshLab isotropic"] = iso
        ms = ml.MeshSet()
        ms.load_new_mesh(obj)
        m = ms.current_mesh()
        v = m.vertex_matrix()
        f = m.face_matrix()
        edge = np.linalg.norm(v[f[:, 0]] - v[f[:, 1]], axis=1).mean()
        rng = np.random.default_rng(1)
        jit = os.path.join(work, name + ".jitter.ply")
        ms.add_mesh(ml.Mesh(v + rng.uniform(-0.4 * edge, 0.4 * edge, v.shape), f))
        ms.save_current_mesh(jit, save_vertex_quality=False, save_vertex_color=False)
        variants["input jittered"] = jit
        for label, path in variants.items():
            a, b = meshlab_count(path), capmesh_count(obj, path)
            ms = ml.MeshSet()
            ms.load_new_mesh(path)
            total += 1
            agree += a == b
            print(f"| {name} | {label} | {ms.current_mesh().face_number()} | {a} | {b} |", flush=True)
    print(f"\nequal counts: {agree} of {total}")


if __name__ == "__main__":
    sys.exit(main())
