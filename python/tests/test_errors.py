"""Bad input raises the matching capmesh exception with the CLI's message; nothing panics."""

import numpy as np
import pytest

import capmesh
from conftest import GENUS2_MESH, OPEN_MESH


def test_missing_file_is_a_read_error_naming_it(cli, tmp_path):
    path = tmp_path / "absent.obj"
    with pytest.raises(capmesh.ReadError) as e:
        capmesh.read_mesh(path)
    assert str(path) in str(e.value)
    done = cli("param", path, "-o", tmp_path / "x.obj", "--quiet")
    assert done.stderr.strip() == f"error: {e.value}"


def test_malformed_file_names_the_line(tmp_path):
    path = tmp_path / "bad.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    with pytest.raises(capmesh.ReadError) as e:
        capmesh.read_mesh(path)
    assert "bad.obj" in str(e.value) and "line 4" in str(e.value)


def test_genus2_is_a_mesh_error_with_the_cli_message(cli, tmp_path):
    v, f = capmesh.read_mesh(GENUS2_MESH)
    with pytest.raises(capmesh.MeshError) as e:
        capmesh.parameterize(v, f)
    assert "genus 2" in str(e.value)
    done = cli("param", GENUS2_MESH, "-o", tmp_path / "x.obj", "--quiet")
    assert done.returncode == 1
    assert done.stderr.strip() == f"error: {GENUS2_MESH}: {e.value}"
    assert isinstance(e.value, capmesh.CapmeshError)


def test_bad_arrays_name_the_element():
    v, f = capmesh.read_mesh(OPEN_MESH)
    bad = f.copy()
    bad[5, 1] = len(v)
    with pytest.raises(capmesh.InputError, match=r"faces\[5\]"):
        capmesh.parameterize(v, bad)
    bad[5, 1] = -1
    with pytest.raises(capmesh.InputError, match=r"faces\[5\]"):
        capmesh.remesh(v, bad)
    nan = v.copy()
    nan[7, 2] = np.nan
    with pytest.raises(capmesh.InputError, match=r"vertices\[7\]"):
        capmesh.parameterize(nan, f)
    with pytest.raises(capmesh.InputError, match=r"shape \(n, 3\)"):
        capmesh.parameterize(v[:, :2], f)
    with pytest.raises(capmesh.InputError, match="float32 or float64"):
        capmesh._capmesh.parameterize(v.astype(np.float16), f)
    with pytest.raises(capmesh.InputError, match="integer"):
        capmesh.parameterize(v, f.astype(np.float64))


def test_bad_options():
    v, f = capmesh.read_mesh(OPEN_MESH)
    with pytest.raises(capmesh.InputError, match="unknown domain 'cube'"):
        capmesh.parameterize(v, f, domain="cube")
    with pytest.raises(capmesh.InputError, match="outside"):
        capmesh.parameterize(v, f, domain="radius=1000")
    with pytest.raises(capmesh.InputError, match="unknown option \"rings\""):
        capmesh.parameterize(v, f, rings=3)
    with pytest.raises(capmesh.InputError, match="smoothing"):
        capmesh.parameterize(v, f, smoothing="strong")
    with pytest.raises(capmesh.InputError, match="optimisation"):
        capmesh.remesh(v, f, optimize="everything")
