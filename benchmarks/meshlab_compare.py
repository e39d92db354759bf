#!/usr/bin/env python3
"""Remeshing comparison of capmesh with the remeshers users pick instead (issue 26, item 5).

Methods, all at the same face count (TARGET, 5000 by default):
- capmesh: the CLI, `target/release/capmesh remesh IN -o OUT --faces N` plus any extra
  arguments from `--capmesh-args` or the CAPMESH_ARGS environment variable (e.g.
  `--capmesh-args "--optimize area"`, to compare variants);
- capmesh_on_surface: the same with `--placement on-surface` (vertices on the input, as the
  paper's pull-back; the default fits the faces to it);
- capmesh_curv: the same with `--sizing curvature` (smaller faces where the surface is curved);
- capmesh_creases: the same with `--keep-creases` (vertices and edges along sharp edges);
- capmesh_surface: the same with `--sizing surface` (equal covered surface areas: a uniform
  vertex density on the surface);
- MeshLab (pymeshlab): isotropic explicit remeshing (target edge length; its defaults keep
  edges whose faces meet at more than 30 degrees as features), the same with feature edges off
  (`featuredeg` 180: every edge may be flipped, collapsed and smoothed across), uniform mesh
  resampling (marching cubes on a distance field, cell size) and screened Poisson
  reconstruction (depth 8, then quadric edge collapse to a face count);
- pyacvd (ACVD clustering, number of clusters; the input is subdivided first when it has
  fewer than 10 points per cluster);
- gpytoolbox `remesh_botsch` (Botsch-Kobbelt isotropic remeshing, 10 iterations, target edge
  length);
- pyinstantmeshes (Instant Meshes in triangle mode, rosy 6 / posy 3, deterministic, target
  vertex count).
Uniform resampling and screened Poisson reconstruct closed surfaces, also from the open
inputs: their faces farther than 1% of the bounding-box diagonal from the input are removed
(which removes the spurious closing sheet of an open input).

Every method's size parameter is tuned (a few secant/bisection steps on log face count against
log parameter) until its face count is within 5% of the target, since the surface distance
falls as faces grow; tuned parameters are cached in benchmarks/results/tuned_params.json
(capmesh's under its arguments and the binary's hash), so reruns skip the tuning. The face
count actually reached is in the table, and a method that does not get within 5% is marked.

Every method runs REPEATS times on every mesh, the methods alternating within each round
(median time reported; python methods are timed around the library call alone, in a worker
process; capmesh is the whole CLI run, process start, I/O, parameterization, remeshing and its
report's metrics included). Every output is scored by `capmesh metrics` (so every metric of
`RemeshMetrics` is in the JSON, and the main ones in the table). A method that fails, crashes
or times out is reported as failed in the table, with its message.

Usage (through benchmarks/meshlab_compare.sh, which builds capmesh and installs the venv):
  meshlab_compare.py [--quick] [--repeats N] [--methods a,b] [--meshes a,b] [--target N]
                     [--capmesh-args "..."] [--retune] [--timeout S] [--tag NAME]
Outputs: benchmarks/results/meshlab_compare{-TAG}.{md,json,png}.
"""

import argparse
import concurrent.futures as cf
import gzip
import hashlib
import json
import math
import multiprocessing as mp
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data")
RESULTS = os.path.join(ROOT, "benchmarks", "results")
CAPMESH = os.path.join(ROOT, "target", "release", "capmesh")
TUNED = os.path.join(RESULTS, "tuned_params.json")
TOLERANCE = 0.05
TUNE_STEPS = 8
MESHES = [
    "open_face_choi",
    "open_hippocampus_sheet_hippunfold",
    "open_lv_endo_rabbit_chaste",
    "open_meg_helmet_babysquid_mne",
    "open_hand_choi",
    "closed_bunny_npm",
    "closed_hippocampus_choi",
    "closed_brain12k_choi",
    "closed_lung_rml_chaste",
    "closed_bird_skull_CPallidusA_choi",
    "closed_brain_choi",
]
QUICK_MESHES = ["open_meg_helmet_babysquid_mne", "closed_bunny_npm", "closed_bird_skull_CPallidusA_choi"]
# capmesh's variants: method key -> the arguments added to `capmesh remesh IN -o OUT --faces N`.
CAPMESH_VARIANTS = {
    "capmesh": [],
    "capmesh_on_surface": ["--placement", "on-surface"],
    "capmesh_curv": ["--sizing", "curvature"],
    "capmesh_creases": ["--keep-creases"],
    "capmesh_surface": ["--sizing", "surface"],
}
# Method key -> (label, kind of size parameter: "count" (faces grow with it) or "length"
# (faces fall as its square)).
# capmesh's variants are labelled by their arguments.
METHODS = {
    **{key: (" ".join(["capmesh", *extra]), "count") for key, extra in CAPMESH_VARIANTS.items()},
    "isotropic": ("MeshLab isotropic explicit remeshing", "length"),
    "isotropic_nf": ("MeshLab isotropic explicit remeshing, feature edges off", "length"),
    "resampling": ("MeshLab uniform mesh resampling", "length"),
    "poisson": ("MeshLab screened Poisson + decimation", "count"),
    "acvd": ("pyacvd (ACVD clustering)", "count"),
    "botsch": ("gpytoolbox remesh_botsch", "length"),
    "instant": ("pyinstantmeshes (Instant Meshes)", "count"),
}

# Metrics of the table and of the best-method summary: (JSON key, column, format, better).
COLUMNS = [
    ("d_face_relative", "d_face_rel", "{:.4f}", "low"),
    ("d_surface_sampled_relative", "d_surf", "{:.2e}", "low"),
    ("hausdorff_distance_relative", "Hausdorff", "{:.2e}", "low"),
    ("mean_min_angle_deg", "mean min angle", "{:.1f}", "high"),
    ("share_faces_angle_below_30", "% < 30 deg", "pct", "low"),
    ("min_angle_deg", "min angle", "{:.1f}", "high"),
    ("max_angle_deg", "max angle", "{:.1f}", "low"),
    ("share_interior_valence_6", "% valence 6", "pct", "high"),
    ("self_intersecting_faces", "self-x faces", "{:d}", "low"),
    ("zero_area_faces", "zero-area", "{:d}", "low"),
]


# ---------------------------------------------------------------------------------------
# Mesh files (numpy only in the parent process).


def read_obj(path):
    v, f = [], []
    with open(path) as fh:
        for line in fh:
            if line.startswith("v "):
                v.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                idx = [int(x.split("/")[0]) for x in line.split()[1:]]
                idx = [i - 1 if i > 0 else len(v) + i for i in idx]
                for k in range(1, len(idx) - 1):
                    f.append([idx[0], idx[k], idx[k + 1]])
    return np.asarray(v, dtype=np.float64), np.asarray(f, dtype=np.int64)


def write_obj(path, v, f):
    f = np.asarray(f)
    if f.ndim == 2 and f.shape[1] == 4:  # quads, if any, split into triangles
        f = np.concatenate([f[:, [0, 1, 2]], f[:, [0, 2, 3]]])
    with open(path, "w") as fh:
        fh.write("".join(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in np.asarray(v, dtype=np.float64)))
        fh.write("".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f))
    return len(f)


def mesh_stats(v, f):
    area = 0.5 * np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1).sum()
    diag = float(np.linalg.norm(v.max(axis=0) - v.min(axis=0)))
    edges = np.concatenate([np.sort(f[:, [0, 1]], axis=1), np.sort(f[:, [1, 2]], axis=1), np.sort(f[:, [2, 0]], axis=1)])
    _, counts = np.unique(edges, axis=0, return_counts=True)
    return {"area": float(area), "diag": diag, "open": bool((counts == 1).any())}


def edge_for(area, faces):
    """Edge length of `faces` equilateral triangles of total area `area`."""
    return math.sqrt(4.0 * area / (math.sqrt(3.0) * faces))


# ---------------------------------------------------------------------------------------
# Library methods, run in a worker process (a crash or a hang there is reported, not fatal).


def _trim_far(ms, original_id, tol_fraction):
    """Delete vertices of the current mesh farther than tol * diagonal from the original."""
    cur = ms.current_mesh_id()
    ms.compute_scalar_by_distance_from_another_mesh_per_vertex(measuremesh=cur, refmesh=original_id, signeddist=False)
    tol = tol_fraction * ms.mesh(original_id).bounding_box().diagonal()
    ms.compute_selection_by_condition_per_vertex(condselect=f"(q > {tol})")
    ms.meshing_remove_selected_vertices()
    ms.meshing_remove_unreferenced_vertices()


def run_library(method, obj, param, out, is_open):
    """Remesh `obj` by `method` with size parameter `param`; write `out` (OBJ). Returns
    (seconds of the remeshing call alone, faces written)."""
    if method in ("isotropic", "isotropic_nf", "resampling", "poisson"):
        import pymeshlab as ml

        ms = ml.MeshSet()
        ms.load_new_mesh(obj)
        original = ms.current_mesh_id()
        diag = ms.current_mesh().bounding_box().diagonal()
        t0 = time.perf_counter()
        if method == "isotropic":
            # featuredeg given although it is MeshLab's default: pymeshlab keeps a filter's last
            # parameters in the process, so the `isotropic_nf` call before would carry over.
            ms.meshing_isotropic_explicit_remeshing(targetlen=ml.PercentageValue(100.0 * param / diag), iterations=10, featuredeg=30.0)
        elif method == "isotropic_nf":
            ms.meshing_isotropic_explicit_remeshing(targetlen=ml.PercentageValue(100.0 * param / diag), iterations=10, featuredeg=180.0)
        elif method == "resampling":
            ms.generate_resampled_uniform_mesh(cellsize=ml.PercentageValue(100.0 * param / diag), offset=ml.PercentageValue(50.0), mergeclosevert=True)
            _trim_far(ms, original, 0.01)
        else:
            ms.compute_normal_per_vertex()
            ms.generate_surface_reconstruction_screened_poisson(depth=8, preclean=True)
            if is_open:
                _trim_far(ms, original, 0.01)
            ms.meshing_decimation_quadric_edge_collapse(targetfacenum=int(round(param)), preservetopology=True)
        seconds = time.perf_counter() - t0
        m = ms.current_mesh()
        return seconds, write_obj(out, m.vertex_matrix(), m.face_matrix())
    v, f = read_obj(obj)
    if method == "acvd":
        import pyacvd
        import pyvista as pv

        t0 = time.perf_counter()
        mesh = pv.PolyData(v, np.hstack([np.full((len(f), 1), 3), f]).ravel())
        clus = pyacvd.Clustering(mesh)
        nclus = int(round(param))
        if mesh.n_points < 10 * nclus:
            clus.subdivide(max(1, math.ceil(math.log(10.0 * nclus / mesh.n_points, 4))))
        clus.cluster(nclus)
        remesh = clus.create_mesh()
        seconds = time.perf_counter() - t0
        faces = remesh.faces.reshape(-1, 4)[:, 1:]
        return seconds, write_obj(out, remesh.points, faces)
    if method == "botsch":
        import gpytoolbox as gp

        t0 = time.perf_counter()
        u, g = gp.remesh_botsch(v, f.astype(np.int32), i=10, h=float(param), project=True)
        seconds = time.perf_counter() - t0
        return seconds, write_obj(out, u, g)
    if method == "instant":
        import pyinstantmeshes as pim

        t0 = time.perf_counter()
        u, g = pim.remesh(v.astype(np.float32), f.astype(np.int32), target_vertex_count=int(round(param)), rosy=6, posy=3, deterministic=True)
        seconds = time.perf_counter() - t0
        return seconds, write_obj(out, u, g)
    raise ValueError(method)


def _quiet():
    """Worker initializer: the libraries' own progress output (Instant Meshes prints every
    step) goes to /dev/null; errors come back as exceptions."""
    import warnings

    warnings.simplefilter("ignore")  # pyacvd's deprecation warnings of pyvista's API
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)


class Worker:
    """One worker process for the library methods, restarted after a crash or a timeout."""

    def __init__(self, timeout):
        self.timeout = timeout
        self.pool = None

    def run(self, *args):
        if self.pool is None:
            self.pool = cf.ProcessPoolExecutor(max_workers=1, mp_context=mp.get_context("spawn"), initializer=_quiet)
        fut = self.pool.submit(run_library, *args)
        try:
            return fut.result(timeout=self.timeout)
        except cf.TimeoutError:
            self.kill()
            raise RuntimeError(f"timed out after {self.timeout:.0f} s")
        except cf.process.BrokenProcessPool:
            self.kill()
            raise RuntimeError("worker process crashed")

    def kill(self):
        if self.pool is not None:
            for p in list(getattr(self.pool, "_processes", {}).values()):
                p.terminate()
            self.pool.shutdown(wait=False, cancel_futures=True)
            self.pool = None


# ---------------------------------------------------------------------------------------


def run_capmesh(obj, param, out, extra, timeout):
    cmd = [CAPMESH, "remesh", "--quiet", obj, "-o", out, "--faces", str(int(round(param)))] + extra
    t0 = time.perf_counter()
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise RuntimeError(f"timed out after {timeout:.0f} s")
    seconds = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError(proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else f"exit {proc.returncode}")
    return seconds, count_faces(out)


def count_faces(path):
    n = 0
    with open(path, "rb") as fh:
        for line in fh:
            if line.startswith(b"f "):
                n += len(line.split()) - 3
    return n


def initial_param(method, stats, target):
    edge = edge_for(stats["area"], target)
    if method in CAPMESH_VARIANTS:
        return target
    return {
        "isotropic": edge,
        "isotropic_nf": edge,
        "resampling": edge,
        "poisson": target,
        "acvd": target / 2.0,
        "botsch": edge,
        "instant": target / 2.0,
    }[method]


def tune(run_once, p0, kind, target):
    """Secant/bisection on log(faces) against log(param) until the face count is within
    TOLERANCE of `target`. Returns (param, faces, steps, within)."""
    below = above = None  # (log p, log faces) with faces below / above the target
    p, tried = p0, []
    for _ in range(TUNE_STEPS):
        faces = run_once(p)
        tried.append((p, faces))
        if abs(faces / target - 1.0) <= TOLERANCE:
            return p, faces, tried, True
        if len(tried) >= 3 and all(abs(t[1] / faces - 1.0) < 0.01 for t in tried[-3:]):
            break  # the count no longer responds to the parameter
        point = (math.log(p), math.log(max(faces, 1)))
        if faces < target:
            below = point
        else:
            above = point
        if below and above and below[0] != above[0] and below[1] != above[1]:
            slope = (above[1] - below[1]) / (above[0] - below[0])
            lp = below[0] + (math.log(target) - below[1]) / slope
            lo, hi = sorted([below[0], above[0]])
            # Secant step, kept inside the bracket (bisection when it leaves it).
            lp = lp if lo < lp < hi else 0.5 * (lo + hi)
            p = math.exp(lp)
        else:
            # One side of the target only: a secant through the last two tries when they
            # give a usable slope (a method whose count responds slowly, e.g. MeshLab's
            # isotropic remeshing coarsening the 48k brain), else the size parameter's own
            # law (faces ~ p or ~ p^-2); steps of at most a factor of 4.
            exponent = 1.0 if kind == "count" else -2.0
            if len(tried) >= 2 and tried[-2][0] != p and tried[-2][1] != faces and tried[-2][1] > 0 and faces > 0:
                secant = (math.log(faces) - math.log(tried[-2][1])) / (math.log(p) - math.log(tried[-2][0]))
                if secant * exponent > 0 and abs(secant) > 0.05:
                    exponent = secant
            step = (target / max(faces, 1)) ** (1.0 / exponent)
            p = p * min(4.0, max(0.25, step))
        if kind == "count" and p >= 1.0:
            p = float(round(p))
    return (*closest_try(tried, p0, target), tried, False)


def closest_try(tried, p0, target):
    """The try whose face count is nearest the target; among those within 1% of it, the one
    whose parameter is nearest the first guess (a method whose count saturates, like MeshLab's
    isotropic remeshing on the 48k brain at about 5700 faces, is not pushed to an absurd edge
    length for the last few faces)."""
    err = lambda t: abs(t[1] / target - 1.0)
    best = min(err(t) for t in tried)
    near = [t for t in tried if err(t) <= best + 0.01]
    p, faces = min(near, key=lambda t: abs(math.log(t[0] / p0)))
    return p, faces


def binary_hash():
    h = hashlib.sha1()
    with open(CAPMESH, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()[:12]


def metrics(original, remeshed):
    out = subprocess.run([CAPMESH, "metrics", original, remeshed, "--json"], capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError("capmesh metrics: " + out.stderr.strip())
    return json.loads(out.stdout)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help=f"1 repeat, meshes {', '.join(QUICK_MESHES)}")
    ap.add_argument("--repeats", type=int, default=int(os.environ.get("REPEATS", "3")))
    ap.add_argument("--methods", default=os.environ.get("METHODS", ""), help="comma-separated keys: " + ",".join(METHODS))
    ap.add_argument("--meshes", default="", help="comma-separated mesh names (default: all 11)")
    ap.add_argument("--target", type=int, default=5000)
    ap.add_argument("--capmesh-args", default=os.environ.get("CAPMESH_ARGS", ""), help="extra arguments of capmesh remesh")
    ap.add_argument("--retune", action="store_true", help="ignore the cached tuned parameters")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds for one run of one method")
    ap.add_argument("--tag", default="", help="suffix of the output files")
    args = ap.parse_args()
    repeats = 1 if args.quick else max(1, args.repeats)
    methods = [m.strip() for m in args.methods.split(",") if m.strip()] or list(METHODS)
    unknown = [m for m in methods if m not in METHODS]
    if unknown:
        ap.error(f"unknown methods {unknown}; known: {list(METHODS)}")
    meshes = [m.strip() for m in args.meshes.split(",") if m.strip()] or (QUICK_MESHES if args.quick else MESHES)
    extra = shlex.split(args.capmesh_args)
    # OpenMP threads (MeshLab's Poisson) that spin while waiting take 4-10 times longer on a
    # machine shared with other work (bunny, screened Poisson: 13.7 s spinning, 3.4 s passive).
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
    target = args.target
    os.makedirs(RESULTS, exist_ok=True)
    cache = {}
    if os.path.exists(TUNED) and not args.retune:
        with open(TUNED) as fh:
            cache = json.load(fh)
    cap_key = "capmesh " + " ".join(extra) + " @" + binary_hash() if any(m.startswith("capmesh") for m in methods) else ""
    worker = Worker(args.timeout)
    work = tempfile.mkdtemp(prefix="capmesh-compare-")
    rows = []
    t_start = time.perf_counter()
    try:
        for name in meshes:
            obj = os.path.join(work, name + ".obj")
            with gzip.open(os.path.join(DATA, name + ".obj.gz"), "rb") as src, open(obj, "wb") as dst:
                dst.write(src.read())
            stats = mesh_stats(*read_obj(obj))

            def run(method, param, out):
                if method in CAPMESH_VARIANTS:
                    return run_capmesh(obj, param, out, extra + CAPMESH_VARIANTS[method], args.timeout)
                return worker.run(method, obj, param, out, stats["open"])

            # Tuning (untimed), or the cached parameter.
            params = {}
            for method in methods:
                key = f"{cap_key + ' ' + method if method.startswith('capmesh') else method}|{name}|{target}"
                if key in cache:
                    params[method] = cache[key]
                    continue
                out = os.path.join(work, f"{name}.{method}.tune.obj")
                kind = METHODS[method][1]
                try:
                    p, faces, tried, within = tune(lambda p: run(method, p, out)[1], initial_param(method, stats, target), kind, target)
                    params[method] = {"param": p, "faces": faces, "within": within, "tried": tried}
                    cache[key] = params[method]
                    with open(TUNED, "w") as fh:
                        json.dump(cache, fh, indent=1, sort_keys=True)
                except Exception as e:  # reported in the table
                    params[method] = {"error": f"tuning: {e}"}
                print(f"{name} {method} tuned: {params[method]}", flush=True)
            # Timed rounds, the methods alternating.
            runs = {m: [] for m in methods}
            for _ in range(repeats):
                for method in methods:
                    if "error" in params[method]:
                        continue
                    out = os.path.join(work, f"{name}.{method}.obj")
                    try:
                        secs, faces = run(method, params[method]["param"], out)
                        runs[method].append((out, secs, ""))
                    except Exception as e:
                        runs[method].append((None, 0.0, str(e)))
            for method in methods:
                label = METHODS[method][0] + (f" {' '.join(extra)}" if method.startswith("capmesh") and extra else "")
                row = {"mesh": name, "method": method, "label": label, "param": params[method].get("param"), "within_tolerance": params[method].get("within"), "seconds": None, "seconds_runs": [], "metrics": None, "error": params[method].get("error", "")}
                if not row["error"]:
                    failed = [r for r in runs[method] if r[0] is None]
                    times = [t for p, t, _ in runs[method] if p is not None]
                    row["seconds_runs"] = times
                    if failed:
                        row["error"] = failed[0][2]
                    else:
                        row["seconds"] = statistics.median(times)
                        try:
                            row["metrics"] = metrics(obj, runs[method][-1][0])
                        except Exception as e:
                            row["error"] = str(e)
                rows.append(row)
                m = row["metrics"]
                print(name, label, "failed: " + row["error"] if not m else f"{row['seconds']:.2f}s faces {m['faces']} d_face_rel {m['d_face_relative']:.4f} d_surf {m['d_surface_sampled_relative']:.2e} min-angle mean {m['mean_min_angle_deg']:.1f} self-x {m['self_intersecting_faces']}", flush=True)
    finally:
        worker.kill()
    total = time.perf_counter() - t_start
    suffix = f"-{args.tag}" if args.tag else ""
    with open(os.path.join(RESULTS, f"meshlab_compare{suffix}.json"), "w") as fh:
        json.dump({"target": target, "repeats": repeats, "capmesh_args": extra, "wall_seconds": total, "rows": rows}, fh, indent=1)
    write_report(rows, target, repeats, extra, total, suffix)
    print(f"total {total:.0f} s", flush=True)


def fmt(value, spec):
    if value is None:
        return ""
    if spec == "pct":
        return f"{100.0 * value:.1f}"
    if spec == "{:d}":
        return str(int(value))
    return spec.format(value)


def cpu_model():
    """The processor's model name (from /proc/cpuinfo; "unknown CPU" elsewhere): timings move
    by a factor of two between the machines CI runs on."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def write_report(rows, target, repeats, extra, total, suffix):
    try:
        import pymeshlab

        versions = f"pymeshlab {getattr(pymeshlab, '__version__', '2025.7.post1')}"
    except Exception:
        versions = "pymeshlab not importable"
    lines = [
        f"# Remeshing: capmesh and the remeshers users pick instead (about {target} faces)",
        "",
        f"Machine: {os.cpu_count()} cores ({cpu_model()}); {versions}; {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; whole run {total / 60:.1f} min.",
        f"capmesh arguments: `--faces N{(' ' + ' '.join(extra)) if extra else ''}`.",
        f"seconds: median of {repeats} runs, the methods alternating within each round (every run's time in the JSON);",
        "library methods timed around the call alone, capmesh as the whole CLI run (process start, I/O, metrics included);",
        f"OMP_WAIT_POLICY={os.environ.get('OMP_WAIT_POLICY', '')} (MeshLab's OpenMP threads do not spin on a shared machine).",
        f"Every method's size parameter (`param`: faces, clusters, vertices or an edge length / cell size) tuned until its",
        f"face count is within {TOLERANCE:.0%} of {target} (`*`: not reached in {TUNE_STEPS} steps; the count reached is in `faces`).",
        "All outputs scored by `capmesh metrics` against the input: d_face_rel = mean |area - mean| / mean area;",
        "d_surf = symmetric face-sampled mean distance / bounding-box diagonal; Hausdorff = one-sided (remesh to input),",
        "largest face-sampled distance / diagonal; angles in degrees (mean over faces of each face's smallest angle,",
        "share of faces with an angle below 30); valence 6 = share of interior vertices; self-x faces = MeshLab's",
        "self-intersecting faces (the input's own count in brackets).",
        "",
        "| mesh | method | param | faces | " + " | ".join(c[1] for c in COLUMNS) + " | seconds |",
        "|---|---|---:|---:|" + "---:|" * len(COLUMNS) + "---:|",
    ]
    for r in rows:
        m = r["metrics"]
        param = "" if r["param"] is None else (f"{r['param']:.4g}" + ("" if r["within_tolerance"] else "*"))
        if m:
            cells = []
            for key, _, spec, _ in COLUMNS:
                cell = fmt(m.get(key), spec)
                if key == "self_intersecting_faces":
                    cell += f" ({m.get('self_intersecting_faces_input', '?')})"
                cells.append(cell)
            lines.append(f"| {r['mesh']} | {r['label']} | {param} | {m['faces']} | " + " | ".join(cells) + f" | {r['seconds']:.2f} |")
        else:
            err = r["error"].replace("|", "/").replace("\n", " ")[:120]
            lines.append(f"| {r['mesh']} | {r['label']} | {param} | failed: {err} |" + " |" * len(COLUMNS) + " |")
    # Best method per metric per mesh (ties listed together).
    short = {m: m for m in METHODS}
    keys = [c for c in COLUMNS if c[0] != "zero_area_faces"] + [("seconds", "seconds", "{:.2f}", "low")]
    lines += ["", "## Best method per metric and mesh", "", "Keys: " + ", ".join(f"`{k}` = {METHODS[k][0]}" for k in METHODS) + ".", ""]
    lines += ["| mesh | " + " | ".join(k[1] for k in keys) + " |", "|---|" + "---|" * len(keys)]
    wins = {}
    for mesh in dict.fromkeys(r["mesh"] for r in rows):
        rs = [r for r in rows if r["mesh"] == mesh and r["metrics"]]
        cells = []
        for key, _, _, better in keys:
            vals = [((r["seconds"] if key == "seconds" else r["metrics"].get(key)), r["method"]) for r in rs]
            vals = [(v, meth) for v, meth in vals if v is not None]
            if not vals:
                cells.append("")
                continue
            best = min(v for v, _ in vals) if better == "low" else max(v for v, _ in vals)
            winners = [meth for v, meth in vals if v == best]
            for w in winners:
                wins.setdefault(key, {}).setdefault(w, 0)
                wins[key][w] += 1
            cells.append(", ".join(short[w] for w in winners))
        lines.append(f"| {mesh} | " + " | ".join(cells) + " |")
    lines += ["", "Meshes on which each method is best (ties count for each):", ""]
    for key, label, _, _ in keys:
        w = wins.get(key, {})
        lines.append(f"- {label}: " + (", ".join(f"{k} {v}" for k, v in sorted(w.items(), key=lambda t: -t[1])) or "none"))
    lines += surface_distance_summary(rows)
    failed = [r for r in rows if not r["metrics"]]
    lines += ["", f"Failed runs: {len(failed)}" + ("" if not failed else " (" + "; ".join(f"{r['mesh']} {r['method']}" for r in failed) + ")."), ""]
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        methods = list(dict.fromkeys(r["method"] for r in rows))
        meshes = list(dict.fromkeys(r["mesh"] for r in rows))
        panels = [("seconds", "seconds", True), ("d_face_relative", "d_face / mean area", True), ("d_surface_sampled_relative", "d_surf / diagonal", True), ("hausdorff_distance_relative", "Hausdorff / diagonal", True), ("mean_min_angle_deg", "mean smallest angle (deg)", False), ("share_faces_angle_below_30", "share of faces with an angle < 30 deg", False), ("share_interior_valence_6", "share of interior valence 6", False), ("self_intersecting_faces", "self-intersecting faces (+1)", True)]
        fig, axes = plt.subplots(2, 4, figsize=(22, 8))
        width = 0.8 / max(1, len(methods))
        for ax, (key, label, log) in zip(axes.ravel(), panels):
            for k, meth in enumerate(methods):
                vals = []
                for mesh in meshes:
                    r = next((r for r in rows if r["mesh"] == mesh and r["method"] == meth), None)
                    v = float("nan")
                    if r and r["metrics"]:
                        v = r["seconds"] if key == "seconds" else r["metrics"][key]
                        v = v + 1 if key == "self_intersecting_faces" else v
                    vals.append(v)
                ax.bar([i + k * width for i in range(len(meshes))], vals, width, label=meth)
            ax.set_xticks([i + 0.4 for i in range(len(meshes))])
            ax.set_xticklabels([m.split("_")[0][0] + ":" + m.split("_")[1] for m in meshes], rotation=40, fontsize=7)
            if log:
                ax.set_yscale("log")
            ax.set_title(label, fontsize=9)
        axes[0][0].legend(fontsize=7)
        fig.tight_layout()
        png = f"meshlab_compare{suffix}.png"
        fig.savefig(os.path.join(RESULTS, png), dpi=100)
        lines.append(f"![metrics per mesh and method]({png})")
    except Exception as e:
        lines.append(f"(plots not made: {e})")
    notes = os.path.join(os.path.dirname(os.path.abspath(__file__)), "meshlab_compare_notes.md")
    if os.path.exists(notes) and not suffix:
        with open(notes) as fh:
            lines += ["", fh.read().rstrip()]
    with open(os.path.join(RESULTS, f"meshlab_compare{suffix}.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")


def surface_distance_summary(rows):
    """Each capmesh variant's sampled surface distance over the best of the other methods on
    each mesh (issue 26: within 10% everywhere, the lowest on at least 5 of 11; with
    `--sizing curvature` the lowest on 9)."""
    meshes = list(dict.fromkeys(r["mesh"] for r in rows))
    variants = [m for m in dict.fromkeys(r["method"] for r in rows) if m.startswith("capmesh")]
    key = "d_surface_sampled_relative"

    def value(mesh, method):
        r = next((r for r in rows if r["mesh"] == mesh and r["method"] == method and r["metrics"]), None)
        return None if r is None else r["metrics"].get(key)

    others = {}
    for mesh in meshes:
        vals = [(value(mesh, m), m) for m in dict.fromkeys(r["method"] for r in rows) if not m.startswith("capmesh")]
        vals = [(v, m) for v, m in vals if v is not None]
        if vals:
            others[mesh] = min(vals)
    if not variants or not others:
        return []
    lines = ["", "## Surface distance against the best other method", "",
             "Each capmesh variant's d_surf over the lowest d_surf of the non-capmesh methods on the mesh (below 1: capmesh lower; that method in brackets).", ""]
    lines += ["| variant | " + " | ".join(meshes) + " | lowest | within 10% |", "|---|" + "---:|" * (len(meshes) + 2)]
    for v in variants:
        cells, lowest, within = [], 0, 0
        for mesh in meshes:
            d = value(mesh, v)
            if d is None or mesh not in others:
                cells.append("")
                continue
            ratio = d / others[mesh][0]
            lowest += ratio < 1.0
            within += ratio <= 1.1
            cells.append(f"{ratio:.2f} ({others[mesh][1]})")
        lines.append(f"| {METHODS[v][0]} | " + " | ".join(cells) + f" | {lowest} of {len(cells)} | {within} of {len(cells)} |")
    return lines


if __name__ == "__main__":
    sys.exit(main())
