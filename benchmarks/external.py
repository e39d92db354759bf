"""Remesh quality on anatomical meshes that are not in the repository (issue 26: "the same figures hold
on anatomical meshes that are not in the repository").

- FreeSurfer's fsaverage5 surfaces (10242 vertices per hemisphere, closed genus 0) ship inside
  nilearn's wheel on PyPI (nilearn/datasets/data/fsaverage5/*.gii.gz). The wheel is downloaded
  (`pip download nilearn==NILEARN --no-deps`, not installed, not committed), the GIFTI surfaces
  are taken from it: pial (the folded outer surface, sulci closed to a few voxels), white (the
  grey/white boundary) and inflated, both hemispheres.
- The Conte69 32k midthickness surfaces (32492 vertices per hemisphere, closed genus 0; Van Essen
  et al. 2012) ship inside BrainSpace's wheel on PyPI (brainspace/datasets/surfaces/*.gii),
  downloaded the same way.
- pymeshlab's sample bone (`pymeshlab/tests/sample_meshes/bone.ply` in the benchmark's venv: a
  long bone, 3022 faces, closed genus 0).
Then `capmesh remesh --faces N` runs on each (N = 5000 and 20000 by default) with the default
options, and the table gives the figures of the issue's bars (the same as benchmarks/variants.py),
each marked where it misses.

    bash benchmarks/external.sh            # writes benchmarks/results/external.{md,json}
"""

import argparse
import gzip
import os
import subprocess
import sys
import tempfile
import zipfile

import pymeshlab

from variants import bar_cells, bar_counts, machine_line, remesh_row, write_report

NILEARN = "0.14.1"
BRAINSPACE = "0.3.0"
SURFACES = ["pial_left", "pial_right", "white_left", "white_right", "infl_left", "infl_right"]


def wheel(work, requirement):
    """The wheel of `requirement` downloaded (not installed) into its own folder of `work`."""
    wheels = os.path.join(work, "wheel_" + requirement.split("==")[0])
    subprocess.run([sys.executable, "-m", "pip", "download", "-q", "--no-deps", "--disable-pip-version-check", "-d", wheels, requirement], check=True)
    return next(os.path.join(wheels, w) for w in os.listdir(wheels) if w.endswith(".whl"))


def surfaces(work):
    """The fsaverage5 GIFTI surfaces of nilearn's wheel and the Conte69 ones of BrainSpace's,
    unpacked into `work`, and pymeshlab's sample bone: name -> path."""
    paths = {}
    with zipfile.ZipFile(wheel(work, f"nilearn=={NILEARN}")) as z:
        for name in SURFACES:
            path = os.path.join(work, f"fsaverage5_{name}.gii")
            with open(path, "wb") as out:
                out.write(gzip.decompress(z.read(f"nilearn/datasets/data/fsaverage5/{name}.gii.gz")))
            paths[name] = path
    with zipfile.ZipFile(wheel(work, f"brainspace=={BRAINSPACE}")) as z:
        for hemi in ["lh", "rh"]:
            path = os.path.join(work, f"conte69_32k_{hemi}.gii")
            with open(path, "wb") as out:
                out.write(z.read(f"brainspace/datasets/surfaces/conte69_32k_{hemi}.gii"))
            paths[f"conte69_32k_{hemi}"] = path
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
                row, r = remesh_row(name, path, os.path.join(work, f"{name}_{faces}.obj"), faces, work, {})
                if r is not None:
                    row["input_faces"] = r["parameterization"]["n_faces"]
                    row["d_surface_sampled_relative"] = r["d_surface_sampled_relative"]
                rows.append(row)
    write(rows, args)


def write(rows, args):
    head = [
        "# Remesh quality on anatomical meshes that are not in the repository",
        "",
        machine_line(),
        f"One run of `bash benchmarks/external.sh`: FreeSurfer's fsaverage5 surfaces from nilearn {NILEARN}'s wheel on PyPI",
        f"and the Conte69 32k midthickness surfaces from BrainSpace {BRAINSPACE}'s wheel",
        "(downloaded at run time, not committed), both hemispheres, and pymeshlab's sample bone (`tests/sample_meshes/bone.ply`",
        "of pymeshlab 2025.7.post1), then",
        f"`capmesh remesh SURFACE --faces N` (N = {args.faces.replace(',', ', ')}) with the default options, timed around the",
        "whole command. Bars of issue 26 (set for 5000 faces): d_face_rel <= 0.035, mean smallest angle >= 48,",
        "<= 2% of faces below 30 degrees, smallest angle >= 15, no more self-intersecting faces than the input;",
        "`misses` names the bars a row misses. d_surf: symmetric face-sampled mean distance over the bounding-box diagonal.",
        "",
        *bar_counts(rows, args.faces),
        "",
        "| surface | input faces | target | faces | d_face_rel | mean min angle | % < 30 deg | min angle | self-x faces (input) | d_surf | mean \\|d_area\\| | seconds | misses |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    write_report(
        "external",
        rows,
        head,
        lambda r: f"| {r['mesh']} | {r['input_faces']} | {r['target']} | {bar_cells(r)} | "
        f"{r['d_surface_sampled_relative']:.2e} | {r['mean_abs_area_distortion']:.4f} | {r['seconds']:.2f} | {', '.join(r['misses']) or '-'} |",
        lambda r: f"| {r['mesh']} | | {r['target']} | | | | | | | | | | exit {r['exit']}: {r['error']} |",
    )


if __name__ == "__main__":
    main()
