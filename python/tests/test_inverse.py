"""CapMap.inverse: cap points back to the input surface (the library's InverseMap)."""

import numpy as np
import pytest

import capmesh
from conftest import CLOSED_MESH, OPEN_MESH


def lift(q):
    """Inverse stereographic projection of disk points (k, 2) onto the unit sphere (the map's
    plane is the cap seen from the south pole: plane = cap[:2] / (1 + cap[2]))."""
    s = (q**2).sum(axis=1, keepdims=True)
    return np.hstack([2 * q / (1 + s), (1 - s) / (1 + s)])


def check_located(v, f, located):
    """Every answer is a point of its face: barycentric weights >= 0 summing to 1, and the
    position their combination of the face's corners."""
    points, faces, bary = located
    assert (faces >= 0).all() and (faces < len(f)).all()
    assert (bary >= -1e-12).all()
    np.testing.assert_allclose(bary.sum(axis=1), 1.0, atol=1e-12)
    np.testing.assert_allclose(points, np.einsum("kc,kcd->kd", bary, v[f[faces]]), rtol=0, atol=1e-9 * np.abs(v).max())


@pytest.mark.parametrize("path", [OPEN_MESH, CLOSED_MESH], ids=["open", "closed"])
def test_the_cap_of_each_vertex_goes_back_to_the_vertex(path):
    v, f = capmesh.read_mesh(path)
    m = capmesh.parameterize(v, f)
    located = m.inverse(m.cap)
    assert isinstance(located, capmesh.InversePoints)
    assert located.points.shape == (len(v), 3) and located.faces.shape == (len(v),) and located.barycentric.shape == (len(v), 3)
    assert located.faces.dtype == np.int64
    check_located(v, f, located)
    # Vertices used by a face only: the cap point of a vertex is a corner of its faces.
    used = np.unique(f)
    np.testing.assert_allclose(located.points[used], v[used], rtol=0, atol=1e-7 * np.abs(v).max())


def test_points_inside_the_faces_are_found_in_the_face_that_holds_them():
    v, f = capmesh.read_mesh(OPEN_MESH)
    m = capmesh.parameterize(v, f)
    rng = np.random.default_rng(7)
    # Random points of random faces, on the map's plane, lifted onto the cap.
    faces = rng.integers(0, len(f), 500)
    w = rng.dirichlet([1.0, 1.0, 1.0], 500)
    q = np.einsum("kc,kcd->kd", w, m.plane[f[faces]])
    points, found, bary = m.inverse(lift(q))
    check_located(v, f, (points, found, bary))
    # The face found holds the point in the plane (it may be a neighbour for a point on an
    # edge): its corners' plane points weighted by the answer give the point back.
    np.testing.assert_allclose(np.einsum("kc,kcd->kd", bary, m.plane[f[found]]), q, atol=1e-9)
    same = found == faces
    assert same.mean() > 0.95
    np.testing.assert_allclose(bary[same], w[same], atol=1e-9)
    np.testing.assert_allclose(points[same], np.einsum("kc,kcd->kd", w, v[f[faces]])[same], atol=1e-9 * np.abs(v).max())


def test_points_off_the_cap_are_reported_not_guessed():
    v, f = capmesh.read_mesh(OPEN_MESH)
    m = capmesh.parameterize(v, f)
    assert m.z_star > 0.5
    below = [np.sqrt(1 - 0.25), 0.0, 0.5]  # on the sphere, below Z*
    outside = [0.0, 0.0, 2.0]  # off the sphere
    nan = [np.nan, 0.0, 1.0]
    inside = m.cap[0]
    points, faces, bary = m.inverse(np.array([below, outside, nan, inside]))
    assert faces.tolist()[:3] == [-1, -1, -1] and faces[3] >= 0
    assert np.isnan(points[:3]).all() and np.isnan(bary[:3]).all()
    assert np.isfinite(points[3]).all()


def test_tolerance_and_a_single_point():
    v, f = capmesh.read_mesh(CLOSED_MESH)
    m = capmesh.parameterize(v, f)
    north = np.array([0.0, 0.0, 1.0]) * (1 + 1e-6)
    assert m.inverse(north).faces.tolist() == [-1]
    one = m.inverse(north, tolerance=1e-5)
    assert one.faces.shape == (1,) and one.faces[0] >= 0
    check_located(v, f, one)


def test_bad_points_and_a_hand_made_map_raise_input_errors():
    v, f = capmesh.read_mesh(OPEN_MESH)
    m = capmesh.parameterize(v, f)
    with pytest.raises(capmesh.InputError, match=r"shape \(k, 3\)"):
        m.inverse(np.zeros((4, 2)))
    with pytest.raises(capmesh.InputError, match="tolerance"):
        m.inverse(m.cap[:2], tolerance=-1.0)
    with pytest.raises(capmesh.InputError, match="capmesh.parameterize"):
        capmesh.CapMap(m.cap, m.plane, m.report).inverse(m.cap)
