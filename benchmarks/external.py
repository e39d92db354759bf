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
- The Conte69 left hemisphere without its medial wall (BrainSpace's `conte69_32k_lh_mask.csv`):
  the cortex as an open disk-like sheet, as surface-based analyses use it.
- Two segmentation surfaces of the MNI152 2009c template, which also ships inside nilearn's wheel
  (nilearn/datasets/data/mni_icbm152_*.nii.gz, 1 mm voxels): the brain (grey + white matter
  probability above 0.5) and the head (T1 above its 60th percentile), each its largest piece with
  its cavities filled, padded, smoothed (Gaussian, 2 voxels) and cut by marching cubes at 0.5:
  closed genus-0 surfaces of about 130k vertices, as a segmented MRI or CT gives them, mapped
  through a decimated copy (docs/method.md section 20). The head once more, not padded below:
  cut by the volume's lower edge, an open surface whose boundary is far shorter than the surface
  is wide (a closed surface with a hole; docs/method.md section 18, "Short boundaries"), remeshed
  as it is and with `--fill-holes` (section 24).
- Three synthetic long bones (marching cubes of a capsule with rounded ends, scikit-image): a shaft
  5-6 times as long as it is wide, where an area-preserving map onto the sphere is anisotropic
  and its transport hardest to start (docs/method.md, "2. Logarithmic and stale Newton steps,
  continuation"), and one of a femur's proportions (a shaft 20 times as long as it is wide,
  heads twice as wide: docs/method.md section 13).
- Two of those bones decimated as users decimate segmentations (pymeshlab's quadric edge
  collapse to 6000 faces, normals preserved; `_quadric`): their shafts become bands of needles
  from end to end, which `remesh` splits for the map (docs/method.md section 25, "Long edges").
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

import nibabel
import numpy as np
import pymeshlab
from scipy import ndimage
from skimage import measure

from meshlab_compare import write_obj
from variants import bar_cells, bar_counts, machine_line, remesh_row, write_report

NILEARN = "0.14.1"
BRAINSPACE = "0.3.0"
SURFACES = ["pial_left", "pial_right", "white_left", "white_right", "infl_left", "infl_right"]
# Synthetic long bones: name -> (shaft half-length, shaft radius, end radius, voxel size).
LONG_BONES = {"long_bone_a": (4.0, 0.6, 1.3, 0.08), "long_bone_b": (5.0, 0.5, 1.2, 0.07), "long_bone_femur": (8.0, 0.4, 0.8, 0.06)}
# Long bones also remeshed after a quadric decimation to this many faces.
QUADRIC_BONES = ["long_bone_b", "long_bone_femur"]
QUADRIC_FACES = 6000


def long_bone(path, half_length, shaft, end, voxel):
    """Marching cubes of a capsule (radius `shaft`, axis `[-half_length, half_length]` on x) with
    two spheres blended onto its ends (a smooth minimum of the distance fields), one end smaller
    and both off the axis, as the epiphyses of a long bone."""
    extent = half_length + end + 0.5
    xs = np.arange(-extent, extent, voxel)
    ys = np.arange(-end - 0.5, end + 0.5, voxel)
    x, y, z = np.meshgrid(xs, ys, ys, indexing="ij")

    def smooth_min(a, b, k=0.8):
        h = np.clip(0.5 + 0.5 * (b - a) / k, 0.0, 1.0)
        return b * (1 - h) + a * h - k * h * (1 - h)

    capsule = np.sqrt((x - np.clip(x, -half_length, half_length)) ** 2 + y**2 + z**2) - shaft
    head = np.sqrt((x + half_length) ** 2 + y**2 + (z - 0.3) ** 2) - end
    condyle = np.sqrt((x - half_length) ** 2 + (y - 0.2) ** 2 + z**2) - 0.8 * end
    vertices, faces, _, _ = measure.marching_cubes(smooth_min(smooth_min(capsule, head), condyle), 0.0, spacing=(voxel,) * 3, allow_degenerate=False)
    write_obj(path, vertices, faces)


def segmentation_surface(path, mask, pad_below=4):
    """The smoothed boundary of `mask`'s largest piece, cavities filled (see the module doc);
    `pad_below` 0 leaves it cut where it meets the volume's lower edge."""
    mask = np.pad(mask, ((4, 4), (4, 4), (pad_below, 4)))
    labels, count = ndimage.label(mask)
    sizes = ndimage.sum(mask, labels, range(1, count + 1))
    piece = ndimage.binary_fill_holes(labels == 1 + int(np.argmax(sizes)))
    vertices, faces, _, _ = measure.marching_cubes(ndimage.gaussian_filter(piece.astype(float), 2.0), 0.5, allow_degenerate=False)
    write_obj(path, vertices, faces)


def mni_surfaces(work, z):
    """The MNI152 brain and head surfaces (see the module doc) from nilearn's wheel `z`: name -> path."""
    def volume(name):
        path = os.path.join(work, f"{name}.nii.gz")
        with open(path, "wb") as out:
            out.write(z.read(f"nilearn/datasets/data/mni_icbm152_{name}_tal_nlin_sym_09a_converted.nii.gz"))
        return np.asarray(nibabel.load(path).get_fdata())
    t1 = volume("t1")
    paths = {name: os.path.join(work, f"{name}.obj") for name in ["mni152_brain", "mni152_head", "mni152_head_cut"]}
    segmentation_surface(paths["mni152_brain"], volume("gm") + volume("wm") > 0.5)
    segmentation_surface(paths["mni152_head"], t1 > np.percentile(t1, 60))
    segmentation_surface(paths["mni152_head_cut"], t1 > np.percentile(t1, 60), pad_below=0)
    return paths


def open_cortex(path, surface, mask):
    """The faces of the GIFTI `surface` whose three corners the CSV `mask` marks 1 (the cortex
    without the medial wall), unused vertices dropped."""
    gii = nibabel.load(surface)
    vertices, faces = (gii.darrays[k].data for k in (0, 1))
    keep = np.loadtxt(mask).astype(bool)[faces].all(axis=1)
    used, inverse = np.unique(faces[keep], return_inverse=True)
    write_obj(path, vertices[used], inverse.reshape(-1, 3))


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
        paths.update(mni_surfaces(work, z))
    with zipfile.ZipFile(wheel(work, f"brainspace=={BRAINSPACE}")) as z:
        for hemi in ["lh", "rh"]:
            path = os.path.join(work, f"conte69_32k_{hemi}.gii")
            with open(path, "wb") as out:
                out.write(z.read(f"brainspace/datasets/surfaces/conte69_32k_{hemi}.gii"))
            paths[f"conte69_32k_{hemi}"] = path
        mask = os.path.join(work, "conte69_32k_lh_mask.csv")
        with open(mask, "wb") as out:
            out.write(z.read("brainspace/datasets/surfaces/conte69_32k_lh_mask.csv"))
    paths["conte69_32k_lh_open"] = os.path.join(work, "conte69_32k_lh_open.obj")
    open_cortex(paths["conte69_32k_lh_open"], paths["conte69_32k_lh"], mask)
    for name, shape in LONG_BONES.items():
        paths[name] = os.path.join(work, f"{name}.obj")
        long_bone(paths[name], *shape)
    for name in QUADRIC_BONES:
        paths[f"{name}_quadric"] = os.path.join(work, f"{name}_quadric.obj")
        quadric_decimation(paths[name], paths[f"{name}_quadric"], QUADRIC_FACES)
    paths["pymeshlab_bone"] = os.path.join(os.path.dirname(pymeshlab.__file__), "tests", "sample_meshes", "bone.ply")
    return paths


def quadric_decimation(source, target, faces):
    """`source` decimated by pymeshlab's quadric edge collapse to `faces` faces (normals
    preserved), written to `target`."""
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(source)
    ms.meshing_decimation_quadric_edge_collapse(targetfacenum=faces, preservenormal=True)
    ms.save_current_mesh(target)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--faces", default="5000,20000", help="comma-separated target face counts (the issue's bars are for 5000)")
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        runs = [(name, path, ()) for name, path in surfaces(work).items()]
        runs += [(f"{name} --fill-holes", path, ("--fill-holes",)) for name, path, _ in runs if name == "mni152_head_cut"]
        for name, path, options in runs:
            for faces in args.faces.split(","):
                out = os.path.join(work, f"{name.split()[0]}_{len(options)}_{faces}.obj")
                row, r = remesh_row(name, path, out, faces, work, {}, options)
                if r is not None:
                    # The map's faces are the input's split 1:4 `subdivided` times (a coarse input),
                    # then each split long edge added two faces (one per side; closed surfaces).
                    row["subdivided"] = r.get("subdivided", 0)
                    row["split_edges"] = r.get("split_edges", 0)
                    row["input_faces"] = (r["parameterization"]["n_faces"] - 2 * row["split_edges"]) // 4 ** row["subdivided"]
                    row["d_surface_sampled_relative"] = r["d_surface_sampled_relative"]
                    row["map_seconds"] = r["parameterization"]["seconds"]
                    row["lambda"] = (r["parameterization"].get("flatten") or {}).get("lambda")
                rows.append(row)
    write(rows, args)


def write(rows, args):
    head = [
        "# Remesh quality on anatomical meshes that are not in the repository",
        "",
        machine_line(),
        f"One run of `bash benchmarks/external.sh`: FreeSurfer's fsaverage5 surfaces from nilearn {NILEARN}'s wheel on PyPI",
        f"and the Conte69 32k midthickness surfaces from BrainSpace {BRAINSPACE}'s wheel",
        "(downloaded at run time, not committed), both hemispheres, the Conte69 left hemisphere without its medial wall",
        "(an open sheet, BrainSpace's mask), the MNI152 template's brain and head segmented and cut by marching cubes",
        "(`segmentation_surface` in the script, nilearn's wheel; `mni152_head_cut`: the head not padded below, open where",
        "the volume cuts it, as it is and with `--fill-holes`), three synthetic long bones (marching cubes, `LONG_BONES` in the script),",
        f"two of them decimated to {QUADRIC_FACES} faces by pymeshlab's quadric edge collapse (`_quadric`), and pymeshlab's sample bone (`tests/sample_meshes/bone.ply` of pymeshlab 2025.7.post1), then",
        f"`capmesh remesh SURFACE --faces N` (N = {args.faces.replace(',', ', ')}) with the default options (but where named), timed around the",
        "whole command. Bars of issue 26 (set for 5000 faces): d_face_rel <= 0.035, mean smallest angle >= 48,",
        "<= 2% of faces below 30 degrees, smallest angle >= 15, no more self-intersecting faces than the input;",
        "`misses` names the bars a row misses. d_surf: symmetric face-sampled mean distance over the bounding-box diagonal.",
        "map s: the parameterization's seconds within the command; lambda: the quasi-conformal factor of the initial map",
        "(closed surfaces 0.2, raised by the fallback when the transport stalls; open surfaces' composite map 0.5).",
        "subdiv: midpoint subdivisions of an input with fewer faces than the remesh, made for its map; split: its edges longer than",
        "three times the remesh's split at their midpoints for the map (docs/method.md section 25).",
        "",
        *bar_counts(rows, args.faces),
        "",
        "| surface | input faces | subdiv | split | target | faces | d_face_rel | mean min angle | % < 30 deg | min angle | self-x faces (input) | d_surf | mean \\|d_area\\| | lambda | map s | seconds | misses |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    write_report(
        "external",
        rows,
        head,
        lambda r: f"| {r['mesh']} | {r['input_faces']} | {r['subdivided']} | {r['split_edges']} | {r['target']} | {bar_cells(r)} | "
        f"{r['d_surface_sampled_relative']:.2e} | {r['mean_abs_area_distortion']:.4f} | {r['lambda'] if r['lambda'] is not None else '-'} | "
        f"{r['map_seconds']:.2f} | {r['seconds']:.2f} | {', '.join(r['misses']) or '-'} |",
        lambda r: f"| {r['mesh']} | | | | {r['target']} | | | | | | | | | | | | exit {r['exit']}: {r['error']} |",
    )


if __name__ == "__main__":
    main()
