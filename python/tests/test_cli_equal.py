"""The package gives the CLI's results on the bundled meshes (same library, same defaults)."""

import json

import numpy as np
import pytest

import capmesh
from conftest import CLOSED_MESH, DATA, OPEN_MESH


@pytest.mark.parametrize("path", [OPEN_MESH, CLOSED_MESH], ids=["open", "closed"])
def test_parameterize_equals_cli(path, cli, tmp_path):
    out, report = tmp_path / "cap.obj", tmp_path / "param.json"
    done = cli("param", path, "-o", out, "--report", report, "--quiet")
    assert done.returncode == 0, done.stderr
    expected = json.loads(report.read_text())

    v, f = capmesh.read_mesh(path)
    m = capmesh.parameterize(v, f)
    assert m.z_star == expected["z_star"]
    assert m.r_star == expected["r_star"]
    assert m.report["kind"] == expected["kind"]
    assert m.report["area_distortion"] == expected["area_distortion"]
    assert m.report["flipped_faces"] == expected["flipped_faces"]
    assert m.cap.shape == (len(v), 3) and m.plane.shape == (len(v), 2)
    cap_cli, faces_cli = capmesh.read_mesh(out)
    np.testing.assert_array_equal(faces_cli, f)
    np.testing.assert_allclose(m.cap, cap_cli, rtol=0, atol=1e-12)
    # The plane is the cap's stereographic projection from the south pole.
    top = m.cap[:, 2] > -0.9
    np.testing.assert_allclose(m.plane[top], m.cap[top, :2] / (1 + m.cap[top, 2:3]), atol=1e-9)


def test_remesh_equals_cli(cli, tmp_path):
    out, report = tmp_path / "remesh.obj", tmp_path / "remesh.json"
    done = cli("remesh", OPEN_MESH, "-o", out, "--faces", 1000, "--report", report, "--quiet")
    assert done.returncode == 0, done.stderr
    expected = json.loads(report.read_text())

    v, f = capmesh.read_mesh(OPEN_MESH)
    rv, rf, rep = capmesh.remesh(v, f, faces_target=1000)
    assert rep["quality"]["faces"] == expected["faces"] == len(rf)
    assert rep["quality"]["d_face"] == expected["d_face"]
    assert rep["quality"]["min_angle_deg"] == expected["min_angle_deg"]
    assert rep["param"]["z_star"] == expected["parameterization"]["z_star"]
    cli_v, cli_f = capmesh.read_mesh(out)
    np.testing.assert_array_equal(rf, cli_f)
    np.testing.assert_allclose(rv, cli_v, rtol=0, atol=1e-12)

    # The sizing keyword is the CLI's --sizing.
    for sizing in ("curvature=2", "surface"):
        done = cli("remesh", OPEN_MESH, "-o", out, "--faces", 1000, "--report", report, "--quiet", "--sizing", sizing)
        assert done.returncode == 0, done.stderr
        by_cli = json.loads(report.read_text())
        _, _, srep = capmesh.remesh(v, f, faces_target=1000, sizing=sizing)
        assert srep["shape"]["sizing"] == by_cli["shape"]["sizing"] == sizing
        assert srep["quality"]["d_face"] == by_cli["d_face"] != expected["d_face"]
    with pytest.raises(capmesh.InputError, match="unknown sizing"):
        capmesh.remesh(v, f, faces_target=1000, sizing="bumpy")

    # The keep_creases keyword is the CLI's --keep-creases.
    done = cli("remesh", OPEN_MESH, "-o", out, "--faces", 1000, "--report", report, "--quiet", "--keep-creases")
    assert done.returncode == 0, done.stderr
    creased = json.loads(report.read_text())
    kv, kf, krep = capmesh.remesh(v, f, faces_target=1000, keep_creases=True)
    assert krep["shape"]["crease_vertices"] == creased["shape"]["crease_vertices"]
    assert krep["quality"]["d_face"] == creased["d_face"]
    _, _, crep = capmesh.remesh(v, f, faces_target=1000, creases="keep")
    assert crep["quality"]["d_face"] == creased["d_face"] and crep["shape"]["keep_creases"]
    # Curvature sizing keeps creases unless creases="off" (the CLI's --creases off).
    _, _, auto = capmesh.remesh(v, f, faces_target=1000, sizing="curvature")
    _, _, off = capmesh.remesh(v, f, faces_target=1000, sizing="curvature", creases="off")
    assert auto["shape"]["keep_creases"] and auto["shape"]["crease_bound_deg"] == 60.0
    assert not off["shape"]["keep_creases"] and off["shape"]["crease_vertices"] == 0
    done = cli("remesh", OPEN_MESH, "-o", out, "--faces", 1000, "--report", report, "--quiet", "--sizing", "curvature", "--creases", "off")
    assert done.returncode == 0, done.stderr
    assert json.loads(report.read_text())["d_face"] == off["quality"]["d_face"]
    with pytest.raises(capmesh.InputError, match="unknown crease handling"):
        capmesh.remesh(v, f, faces_target=1000, creases="sharp")
    _, _, bent = capmesh.remesh(v, f, faces_target=1000, sizing="curvature", crease_angle=45)
    assert bent["shape"]["crease_bound_deg"] == 45.0
    with pytest.raises(capmesh.InputError, match="crease_angle = 200"):
        capmesh.remesh(v, f, faces_target=1000, crease_angle=200)
    # The library refuses a shape option out of range, whatever sets it.
    with pytest.raises(capmesh.InputError, match="shape_weight = NaN"):
        capmesh.remesh(v, f, faces_target=1000, shape_weight=float("nan"))
    cli_v, cli_f = capmesh.read_mesh(out)

    # metrics() is `capmesh metrics --json`.
    done = cli("metrics", OPEN_MESH, out, "--json")
    assert done.returncode == 0, done.stderr
    assert capmesh.metrics((v, f), (cli_v, cli_f)) == json.loads(done.stdout)

    # The placement keyword is the CLI's --placement (fitted by default, above).
    done = cli("remesh", OPEN_MESH, "-o", out, "--faces", 1000, "--report", report, "--quiet", "--placement", "on-surface")
    assert done.returncode == 0, done.stderr
    on_surface = json.loads(report.read_text())
    pv, pf, prep = capmesh.remesh(v, f, faces_target=1000, placement="on-surface")
    assert prep["fit"]["fitted"] is False and on_surface["fit"]["fitted"] is False and expected["fit"]["fitted"] is True
    assert prep["quality"]["d_surface_sampled"] == on_surface["d_surface_sampled"]
    with pytest.raises(capmesh.InputError, match="unknown vertex placement"):
        capmesh.remesh(v, f, faces_target=1000, placement="floating")

    # The fill_holes keyword is the CLI's --fill-holes: the helmet's opening filled.
    done = cli("remesh", OPEN_MESH, "-o", out, "--faces", 1000, "--report", report, "--quiet", "--fill-holes")
    assert done.returncode == 0, done.stderr
    filled = json.loads(report.read_text())
    hv, hf, hrep = capmesh.remesh(v, f, faces_target=1000, fill_holes=True)
    assert hrep["filled_holes"] == filled["filled_holes"] == 1 and expected["filled_holes"] == 0
    assert hrep["quality"]["d_face"] == filled["d_face"]

    # The no_subdivide keyword is the CLI's --no-subdivide: the helmet (4190 faces) at 5000
    # faces is mapped subdivided by default.
    done = cli("remesh", OPEN_MESH, "-o", out, "--faces", 5000, "--report", report, "--quiet", "--no-subdivide")
    assert done.returncode == 0, done.stderr
    plain = json.loads(report.read_text())
    _, _, prep_plain = capmesh.remesh(v, f, faces_target=5000, no_subdivide=True)
    _, _, prep_fine = capmesh.remesh(v, f, faces_target=5000)
    assert plain["subdivided"] == prep_plain["subdivided"] == 0 and prep_fine["subdivided"] == 1
    assert prep_plain["quality"]["d_face"] == plain["d_face"]


def test_fine_map_keyword():
    """fine_map is the CLI's --fine-map: the 48k brain at 5000 faces is mapped through a copy
    sized to the remesh by default, at one level with it."""
    v, f = capmesh.read_mesh(DATA / "closed_brain_choi.obj.gz")
    _, _, copy = capmesh.remesh(v, f, faces_target=5000)
    _, _, fine = capmesh.remesh(v, f, faces_target=5000, fine_map=True)
    # 1.2 copy vertices per remesh face, or an eighth of the input's 48487 when that is more.
    assert copy["param"]["multilevel"]["coarse_vertices"] == max(6000, 48487 // 8)
    assert fine["param"]["multilevel"] is None


def test_lat_long_grid_and_options():
    v, f = capmesh.read_mesh(OPEN_MESH)
    rv, rf, rep = capmesh.remesh(v, f, lat_long=(8, 16), optimize="area", search_sites=0)
    assert rep["optimize"] == "area"
    assert rep["param"]["search_sites"] is None
    assert len(rf) == rep["quality"]["faces"] > 100


def test_multilevel_options_match_the_cli(cli, tmp_path):
    # Thresholds lowered so that the bundled closed mesh takes the multilevel path (issue 27).
    args = ["--multilevel-above", 1000, "--coarse-vertices", 700]
    out, report = tmp_path / "cap.obj", tmp_path / "param.json"
    done = cli("param", CLOSED_MESH, "-o", out, "--report", report, "--quiet", *args)
    assert done.returncode == 0, done.stderr
    expected = json.loads(report.read_text())
    assert expected["multilevel"]["coarse_vertices"] == 700
    v, f = capmesh.read_mesh(CLOSED_MESH)
    m = capmesh.parameterize(v, f, multilevel_above=1000, coarse_vertices=700)
    assert m.report["multilevel"] == expected["multilevel"] | {k: m.report["multilevel"][k] for k in ("decimate_seconds", "coarse_seconds", "prolong_seconds")}
    assert m.report["area_distortion"] == expected["area_distortion"]
    assert capmesh.parameterize(v, f).report["multilevel"] is None


@pytest.mark.parametrize("vdtype", [np.float32, np.float64])
@pytest.mark.parametrize("fdtype", [np.int32, np.int64, np.uint32])
def test_dtypes(vdtype, fdtype):
    v, f = capmesh.read_mesh(OPEN_MESH)
    reference = capmesh.parameterize(v.astype(vdtype).astype(np.float64), f, domain="hemisphere")
    m = capmesh.parameterize(v.astype(vdtype), f.astype(fdtype), domain="hemisphere")
    assert m.z_star == pytest.approx(0.0)
    np.testing.assert_array_equal(m.cap, reference.cap)


def test_strided_arrays_are_read_in_place():
    v, f = capmesh.read_mesh(OPEN_MESH)
    wide = np.zeros((len(v), 6))
    wide[:, ::2] = v
    a = capmesh.parameterize(v, f, domain="disk")
    b = capmesh.parameterize(wide[:, ::2], np.asfortranarray(f), domain="disk")
    np.testing.assert_array_equal(a.cap, b.cap)
    assert a.z_star is None


def test_write_read_round_trip(tmp_path):
    v, f = capmesh.read_mesh(OPEN_MESH)
    for name in ["m.ply", "m.off", "m.obj", "m.gii"]:
        capmesh.write_mesh(tmp_path / name, v, f)
        v2, f2 = capmesh.read_mesh(tmp_path / name)
        np.testing.assert_array_equal(f2, f)
        np.testing.assert_allclose(v2, v, atol=1e-5 * np.abs(v).max())


def test_harmonics_equals_cli(cli, tmp_path):
    out, report, coefficients = tmp_path / "rec.obj", tmp_path / "h.json", tmp_path / "c.json"
    done = cli("harmonics", OPEN_MESH, "--order", 6, "-o", out, "--report", report, "--coefficients", coefficients, "--quiet")
    assert done.returncode == 0, done.stderr
    expected = json.loads(report.read_text())

    v, f = capmesh.read_mesh(OPEN_MESH)
    rec, coef, rep = capmesh.harmonics(v, f, order=6)
    assert coef.shape == ((6 + 1) ** 2, 3)
    assert rep["z_star"] == expected["z_star"]
    assert rep["errors_by_order"] == expected["errors_by_order"]
    cli_v, cli_f = capmesh.read_mesh(out)
    np.testing.assert_array_equal(cli_f, f)
    np.testing.assert_allclose(rec, cli_v, rtol=0, atol=1e-12)
