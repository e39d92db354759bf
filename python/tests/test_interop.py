"""Interop with trimesh and nibabel (both installed by .ci/run, so these tests never skip): a
GIFTI surface written by nibabel goes in, a remesh goes out as GIFTI that nibabel reads, and
trimesh takes the arrays as they are."""

import nibabel as nib
import numpy as np
import trimesh

import capmesh
from conftest import CLOSED_MESH, OPEN_MESH


def test_gifti_from_nibabel_in_remesh_out(tmp_path):
    v, f = capmesh.read_mesh(OPEN_MESH)
    surface = nib.gifti.GiftiImage(darrays=[
        nib.gifti.GiftiDataArray(v.astype(np.float32), intent="NIFTI_INTENT_POINTSET", datatype="NIFTI_TYPE_FLOAT32"),
        nib.gifti.GiftiDataArray(f.astype(np.int32), intent="NIFTI_INTENT_TRIANGLE", datatype="NIFTI_TYPE_INT32"),
    ])
    nib.save(surface, tmp_path / "in.surf.gii")

    gv, gf = capmesh.read_mesh(tmp_path / "in.surf.gii")
    np.testing.assert_array_equal(gf, f)
    np.testing.assert_array_equal(gv, v.astype(np.float32))
    rv, rf, report = capmesh.remesh(gv, gf, faces_target=800)
    capmesh.write_mesh(tmp_path / "out.surf.gii", rv, rf)

    back = nib.load(tmp_path / "out.surf.gii")
    points, triangles = back.agg_data(("pointset", "triangle"))
    assert triangles.shape == (report["quality"]["faces"], 3)
    np.testing.assert_array_equal(triangles, rf)
    np.testing.assert_allclose(points, rv, rtol=1e-6, atol=1e-4)


def test_trimesh_round_trip():
    v, f = capmesh.read_mesh(CLOSED_MESH)
    source = trimesh.Trimesh(vertices=v, faces=f, process=False)
    rv, rf, report = capmesh.remesh(source.vertices, source.faces, faces_target=1000)
    remeshed = trimesh.Trimesh(vertices=rv, faces=rf, process=False)
    # A closed genus-0 input gives a closed genus-0 remesh.
    assert remeshed.is_watertight
    assert remeshed.euler_number == 2
    assert abs(remeshed.area / source.area - 1) < 0.1  # a coarser inscribed surface
    # The metrics agree with the report the remesh gave.
    assert capmesh.metrics((source.vertices, source.faces), (rv, rf))["d_face"] == report["quality"]["d_face"]
