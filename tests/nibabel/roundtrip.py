"""nibabel's half of the GIFTI / FreeSurfer round trip (run by .ci/run).

Reads the manifest written by `cargo run --release --example nibabel_roundtrip -- OUT_DIR`
and checks, with nibabel, that
  - every real file in tests/data/neuro gives nibabel exactly the arrays capmesh read from it;
  - every file capmesh wrote (GIFTI in 3 encodings x float32/float64 x both byte orders, and
    FreeSurfer) gives nibabel the source surface, rounded to float32 where the file is float32.
Exits non-zero with the list of mismatches.

    python tests/nibabel/roundtrip.py OUT_DIR
"""

import gzip
import json
import sys
import tempfile

import nibabel as nib
import numpy as np
from nibabel.freesurfer import io as fsio


def surface(path):
    """(coordinates, triangles) as nibabel reads them."""
    if path.endswith((".gii", ".gii.gz")):
        img = nib.load(path)
        coords = img.get_arrays_from_intent("NIFTI_INTENT_POINTSET")[0].data
        faces = img.get_arrays_from_intent("NIFTI_INTENT_TRIANGLE")[0].data
        return coords, faces
    if path.endswith(".gz"):
        with gzip.open(path, "rb") as src, tempfile.NamedTemporaryFile(delete=False) as dst:
            dst.write(src.read())
        path = dst.name
    return fsio.read_geometry(path)


def attributes(path):
    """Per-vertex arrays as nibabel reads them (one per column of a 2-D data array)."""
    if not path.endswith((".gii", ".gii.gz")):
        return [fsio.read_morph_data(path)]
    out = []
    for d in nib.load(path).darrays:
        data = d.data if d.data.ndim == 1 else d.data.T
        out.extend([data] if data.ndim == 1 else list(data))
    return out


def main(out_dir):
    with open(f"{out_dir}/manifest.json") as f:
        entries = json.load(f)
    errors, checked = [], 0
    for e in entries:
        name = e["file"]
        if e["kind"] == "read_attributes":
            theirs = attributes(name)
            if len(theirs) != len(e["arrays"]):
                errors.append(f"{name}: nibabel has {len(theirs)} arrays, capmesh {len(e['arrays'])}")
                continue
            for k, (a, t) in enumerate(zip(e["arrays"], theirs)):
                ours = np.fromfile(a["path"], dtype="<f4" if a["type"] == "f32" else "<i4")
                t = t.astype(np.float32 if a["type"] == "f32" else np.int32)
                if not np.array_equal(ours, t, equal_nan=a["type"] == "f32"):
                    errors.append(f"{name}: array {k} differs")
            checked += 1
            continue
        coords, faces = surface(name)
        vertices = np.fromfile(e["vertices"], dtype="<f8").reshape(-1, 3)
        triangles = np.fromfile(e["faces"], dtype="<u4").reshape(-1, 3)
        if e.get("float32"):
            vertices = vertices.astype(np.float32).astype(np.float64)
        if e["kind"] == "written_gifti":
            itemsize = 4 if e["float32"] else 8
            if coords.dtype.kind != "f" or coords.dtype.itemsize != itemsize:
                errors.append(f"{name}: nibabel reads {coords.dtype}, expected {itemsize}-byte floats")
        if not np.array_equal(coords.astype(np.float64), vertices):
            errors.append(f"{name}: coordinates differ (max {np.abs(coords - vertices).max()})")
        if not np.array_equal(faces.astype(np.int64), triangles.astype(np.int64)):
            errors.append(f"{name}: triangles differ")
        checked += 1
    for line in errors:
        print("MISMATCH", line)
    print(f"nibabel {nib.__version__}: {checked} files checked, {len(errors)} mismatches")
    return 1 if errors or checked != len(entries) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
