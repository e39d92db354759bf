"""Remesh quality on anatomical meshes that are not in the repository (issue 26: "the same figures hold
on anatomical meshes that are not in the repository").

- FreeSurfer's fsaverage5 surfaces (10242 vertices per hemisphere, closed genus 0) ship inside
  nilearn's wheel on PyPI (nilearn/datasets/data/fsaverage5/*.gii.gz). The wheel is downloaded
  (`pip download nilearn==NILEARN --no-deps`, not installed, not committed), the GIFTI surfaces
  are taken from it: pial (the folded outer surface, sulci closed to a few voxels), white (the
  grey/white boundary) and inflated, both hemispheres.
- pymeshlab's sample bone (`pymeshlab/tests/sample_meshes/bone.ply` in the benchmark's venv: a
  long bone, 3022 faces, closed genus 0).
Then `capmesh remesh --faces N` runs on each (N = 5000 and 20000 by default) with the default
options, and the table gives the figures of the issue's bars (the same as benchmarks/variants.py),
each marked where it misses.

    bash benchmarks/external.sh            # writes benchmarks/results/external.{md,json}
"""

import argparse
import gzip
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
import zipfile

import pymeshlab

from variants import CAPMESH, RESULTS, misses

NILEARN = "0.14.1"
SURFACES = ["pial_left", "pial_right", "white_left", "white_right", "infl_left", "infl_right"]


def surfaces(work):
    """The fsaverage5 GIFTI surfaces of nilearn's wheel, unpacked into `work`, and pymeshlab's
    sample bone: name -> path."""
    wheels = os.path.join(work, "wheel")
    subprocess.run([sys.executable, "-m", "pip", "download", "-q", "--no-deps", "--disable-pip-version-check", "-d", wheels, f"nilearn=={NILEARN}"], check=True)
    wheel = next(os.path.join(wheels, w) for w in os.listdir(wheels) if w.endswith(".whl"))
    paths = {}
    with zipfile.ZipFile(wheel) as z:
        for name in SURFACES:
            path = os.path.join(work, f"fsaverage5_{name}.gii")
            with open(path, "wb") as out:
                out.write(gzip.decompress(z.read(f"nilearn/datasets/data/fsaverage5/{name}.gii.gz")))
            paths[name] = path
    paths["pymeshlab_bone"] = os.path.join(os.path.dirname(pymeshlab.__file__), "tests", "sample_meshes", "bone.ply")
    return paths


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--faces", default="5000,20000", help="comma-separated target face counts (the issue's bars are for 5000)")
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for name, path in surfaces(work).items():
            for faces in args.faces.split(","):
                out = os.path.join(work, f"{name}_{faces}.obj")
                report = out + ".json"
                t = time.perf_counter()
                run = subprocess.run([CAPMESH, "remesh", path, "-o", out, "--faces", faces, "--report", report, "--quiet"], capture_output=True, text=True)
                seconds = time.perf_counter() - t
                if run.returncode != 0:
                    rows.append({"mesh": name, "target": int(faces), "error": run.stderr.strip().replace(work + os.sep, "")[-300:], "exit": run.returncode})
                    print(f"{name} {faces}: exit {run.returncode}", file=sys.stderr)
                    continue
                r = json.load(open(report))
                row = {
                    "mesh": name, "target": int(faces), "input_faces": r["parameterization"]["n_faces"], "faces": r["faces"],
                    "d_face_relative": r["d_face_relative"], "mean_min_angle_deg": r["mean_min_angle_deg"],
                    "share_faces_angle_below_30": r["share_faces_angle_below_30"], "min_angle_deg": r["min_angle_deg"],
                    "self_intersecting_faces": r["self_intersecting_faces"], "self_intersecting_faces_input": r["self_intersecting_faces_input"],
                    "d_surface_sampled_relative": r["d_surface_sampled_relative"],
                    "mean_abs_area_distortion": r["parameterization"]["area_distortion"]["mean_abs"], "seconds": seconds,
                }
                row["misses"] = misses(name, r)
                rows.append(row)
                print(f"{name} {faces}: {row['faces']} faces, mean {row['mean_min_angle_deg']:.2f}, min {row['min_angle_deg']:.1f} {' '.join(row['misses'])}", file=sys.stderr)
    write(rows, args)


def write(rows, args):
    os.makedirs(RESULTS, exist_ok=True)
    with open(os.path.join(RESULTS, "external.json"), "w") as f:
        json.dump(rows, f, indent=1)
    ok = [r for r in rows if "error" not in r]
    lines = [
        "# Remesh quality on anatomical meshes that are not in the repository",
        "",
        f"Machine: {platform.machine()}, {os.cpu_count()} cores; {platform.platform()}; {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}.",
        f"One run of `bash benchmarks/external.sh`: FreeSurfer's fsaverage5 surfaces from nilearn {NILEARN}'s wheel on PyPI",
        "(downloaded at run time, not committed), both hemispheres, and pymeshlab's sample bone (`tests/sample_meshes/bone.ply`",
        "of pymeshlab 2025.7.post1), then",
        f"`capmesh remesh SURFACE --faces N` (N = {args.faces.replace(',', ', ')}) with the default options, timed around the",
        "whole command. Bars of issue 26 (set for 5000 faces): d_face_rel <= 0.035, mean smallest angle >= 48,",
        "<= 2% of faces below 30 degrees, smallest angle >= 15, no more self-intersecting faces than the input;",
        "`misses` names the bars a row misses. d_surf: symmetric face-sampled mean distance over the bounding-box diagonal.",
        "",
        *[f"Rows meeting every bar at {n} faces: {sum(1 for r in ok if r['target'] == int(n) and not r['misses'])} of {sum(1 for r in rows if r['target'] == int(n))}." for n in args.faces.split(",")],
        "",
        "| surface | input faces | target | faces | d_face_rel | mean min angle | % < 30 deg | min angle | self-x faces (input) | d_surf | mean \\|d_area\\| | seconds | misses |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    for r in rows:
        if "error" in r:
            lines.append(f"| {r['mesh']} | | {r['target']} | | | | | | | | | | exit {r['exit']}: {r['error']} |")
            continue
        lines.append(
            f"| {r['mesh']} | {r['input_faces']} | {r['target']} | {r['faces']} | {r['d_face_relative']:.4f} | {r['mean_min_angle_deg']:.2f} | "
            f"{100 * r['share_faces_angle_below_30']:.2f} | {r['min_angle_deg']:.1f} | {r['self_intersecting_faces']} ({r['self_intersecting_faces_input']}) | "
            f"{r['d_surface_sampled_relative']:.2e} | {r['mean_abs_area_distortion']:.4f} | {r['seconds']:.2f} | {', '.join(r['misses']) or '-'} |"
        )
    with open(os.path.join(RESULTS, "external.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
