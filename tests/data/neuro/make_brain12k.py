"""Write the brain12k GIFTI and FreeSurfer test files of tests/data/neuro with nibabel.

Source: tests/data/closed_brain12k_choi.obj.gz (a real cortical surface, 12502 vertices,
25000 triangles, Apache-2.0; see tests/data/NOTICE.md). Writes, next to this script:

  brain12k.surf.gii.gz     GIFTI surface, GZipBase64Binary, float32 coordinates, int32 triangles;
                           the XML gzip-compressed too (270 KB instead of 358 KB)
  brain12k.pial.gz         the same surface as a FreeSurfer triangle surface, gzip-compressed
  brain12k_curv.shape.gii  its mean curvature (float32, GZipBase64Binary GIFTI shape file)
  brain12k.curv            the same values as a FreeSurfer curvature file (new format)

The coordinates are the OBJ's decimals rounded to float32. The mean curvature is computed here
in float64 with the cotangent Laplacian: H_i = -(L x)_i . n_i / 2, where
(L x)_i = sum_j (cot a_ij + cot b_ij) (x_j - x_i) / (2 A_i), A_i is a third of the area of the
triangles around vertex i and n_i their area-weighted unit normal; H is in 1/(mesh unit),
positive where the surface is convex (a sphere of radius r has H = 1/r), then stored as float32.

    python -m venv /tmp/nib && /tmp/nib/bin/pip install nibabel==5.4.2
    /tmp/nib/bin/python tests/data/neuro/make_brain12k.py
"""

import gzip
import os
import tempfile

import nibabel as nib
import numpy as np
from nibabel.freesurfer import io as fsio

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.join(HERE, "..", "closed_brain12k_choi.obj.gz")
NOTE = "made with nibabel by tests/data/neuro/make_brain12k.py from closed_brain12k_choi.obj.gz (Apache-2.0)"


def read_obj(path):
    vertices, faces = [], []
    with gzip.open(path, "rt") as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vertices.append([float(x) for x in parts[1:4]])
            elif parts[0] == "f":
                faces.append([int(p.split("/")[0]) - 1 for p in parts[1:4]])
    return np.array(vertices, dtype=np.float64), np.array(faces, dtype=np.int32)


def mean_curvature(x, faces):
    n = len(x)
    laplace = np.zeros((n, 3))
    area = np.zeros(n)
    normal = np.zeros((n, 3))
    p = [x[faces[:, k]] for k in range(3)]
    cross = np.cross(p[1] - p[0], p[2] - p[0])
    twice_area = np.linalg.norm(cross, axis=1)
    for k in range(3):
        np.add.at(area, faces[:, k], twice_area / 6.0)
        np.add.at(normal, faces[:, k], cross)
        # The angle at corner k is opposite the edge (i, j).
        i, j = (k + 1) % 3, (k + 2) % 3
        u, v = p[i] - p[k], p[j] - p[k]
        cot = np.einsum("ij,ij->i", u, v) / twice_area
        w = (cot[:, None] * (p[j] - p[i]))
        np.add.at(laplace, faces[:, i], w)
        np.add.at(laplace, faces[:, j], -w)
    laplace /= 2.0 * area[:, None]
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    return -np.einsum("ij,ij->i", laplace, normal) / 2.0


def save_gzipped(image, name, write=None):
    """Write `name` through a temporary file, then gzip it (no time stamp) next to this script."""
    with tempfile.TemporaryDirectory() as tmp:
        plain = os.path.join(tmp, name)
        if write is None:
            nib.save(image, plain)
        else:
            write(plain)
        with open(plain, "rb") as src, gzip.GzipFile(os.path.join(HERE, name + ".gz"), "wb", 9, mtime=0) as dst:
            dst.write(src.read())


def main():
    x, faces = read_obj(SOURCE)
    assert (len(x), len(faces)) == (12502, 25000), (len(x), len(faces))
    coords = x.astype(np.float32)
    curv = mean_curvature(x, faces).astype(np.float32)
    meta = nib.gifti.GiftiMetaData({"Description": NOTE})

    surface = nib.gifti.GiftiImage(meta=meta)
    surface.add_gifti_data_array(nib.gifti.GiftiDataArray(
        coords, intent="NIFTI_INTENT_POINTSET", datatype="NIFTI_TYPE_FLOAT32", encoding="GIFTI_ENCODING_B64GZ"))
    surface.add_gifti_data_array(nib.gifti.GiftiDataArray(
        faces, intent="NIFTI_INTENT_TRIANGLE", datatype="NIFTI_TYPE_INT32", encoding="GIFTI_ENCODING_B64GZ"))
    save_gzipped(surface, "brain12k.surf.gii")

    shape = nib.gifti.GiftiImage(meta=nib.gifti.GiftiMetaData({"Description": NOTE}))
    shape.add_gifti_data_array(nib.gifti.GiftiDataArray(
        curv, intent="NIFTI_INTENT_SHAPE", datatype="NIFTI_TYPE_FLOAT32", encoding="GIFTI_ENCODING_B64GZ",
        meta=nib.gifti.GiftiMetaData({"Name": "mean curvature"})))
    nib.save(shape, os.path.join(HERE, "brain12k_curv.shape.gii"))

    save_gzipped(None, "brain12k.pial", lambda path: fsio.write_geometry(
        path, coords, faces, create_stamp=f"created by capmesh tests: {NOTE}"))
    fsio.write_morph_data(os.path.join(HERE, "brain12k.curv"), curv, fnum=len(faces))


if __name__ == "__main__":
    main()
