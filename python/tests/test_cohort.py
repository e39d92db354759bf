"""capmesh.cohort.shape: the rows of `capmesh shape`'s CSV as a DataFrame, serially and on a
local Dask cluster (2 worker processes, 1 thread each), including a worker killed while it
runs a mesh."""

import os
import shutil
import sys

import cloudpickle
import numpy as np
import pandas as pd
import pytest
from distributed import Client, LocalCluster
from distributed.diagnostics.plugin import WorkerPlugin

import capmesh
from capmesh import cohort
from conftest import CLOSED_MESH, DATA, GENUS2_MESH, OPEN_MESH

# Two closed, one open and one that fails (genus 2).
MESHES = [CLOSED_MESH, OPEN_MESH, DATA / "closed_bird_skull_CPallidusA_choi.obj.gz", GENUS2_MESH]
TEXT = ["file", "status", "quality", "kind", "error", "modified", "sha256"]


@pytest.fixture(scope="module")
def cohort_dir(tmp_path_factory):
    """The meshes copied into a directory, with a file that is not a mesh (skipped) and one in
    a subdirectory (searched)."""
    root = tmp_path_factory.mktemp("cohort")
    (root / "sub").mkdir()
    for i, mesh in enumerate(MESHES):
        shutil.copy(mesh, (root / "sub" if i == 0 else root) / mesh.name)
    (root / "notes.txt").write_text("not a mesh\n")
    return root


@pytest.fixture(scope="module")
def serial(cohort_dir):
    return cohort.shape([cohort_dir])


def read_cli_csv(path):
    df = pd.read_csv(path, dtype={c: str for c in TEXT})
    for c in TEXT:
        df[c] = df[c].fillna("")
    return df


def test_serial_equals_the_cli_csv(cli, cohort_dir, serial, tmp_path):
    csv = tmp_path / "shape.csv"
    done = cli("shape", cohort_dir, "--csv", csv, "--quiet")
    assert done.returncode == 1, done.stderr  # one mesh fails: the CLI exits 1 after the CSV
    expected = read_cli_csv(csv)
    assert list(serial.columns) == list(expected.columns) == cohort.COLUMNS
    assert len(serial) == len(MESHES) == len(expected)
    for c in TEXT:
        assert serial[c].fillna("").tolist() == expected[c].tolist(), c
    for c in ["vertices", "faces", "bytes"]:
        assert serial[c].astype("float64").fillna(-1).tolist() == pd.to_numeric(expected[c]).fillna(-1).tolist(), c
    for c in ["z_star", "aspect_ratio", "ellipsoid_aspect_ratio", "sigma1", "sigma2", "sigma3", "mean_abs_area_distortion", "lambda"]:
        np.testing.assert_allclose(serial[c].to_numpy(), pd.to_numeric(expected[c]).to_numpy(), rtol=1e-9, equal_nan=True, err_msg=c)
    assert serial["status"].tolist().count("failed") == 1
    failed = serial[serial["status"] == "failed"].iloc[0]
    assert failed["file"].endswith(GENUS2_MESH.name) and "genus 2" in failed["error"]
    assert pd.isna(failed["vertices"]) and np.isnan(failed["aspect_ratio"])
    open_row = serial[serial["kind"] == "open"].iloc[0]
    assert np.isnan(open_row["lambda"]) and open_row["z_star"] > 0


def test_files_and_options_as_the_cli(cohort_dir):
    files = cohort.mesh_files([cohort_dir])
    assert len(files) == len(MESHES) and not any(f.endswith(".txt") for f in files)
    assert files == sorted(files) and str(cohort_dir / "sub" / MESHES[0].name) in files
    assert cohort.mesh_files(files[:1] * 2) == files[:1]
    with pytest.raises(capmesh.InputError, match="unknown harmonic basis"):
        cohort.shape(files, basis="xyz")
    with pytest.raises(capmesh.InputError, match="spherical cap harmonics only"):
        cohort.shape(files, boundary="dirichlet")
    with pytest.raises(capmesh.InputError, match="no mesh files"):
        cohort.shape([])


def test_a_missing_file_is_a_failed_row(tmp_path):
    missing = tmp_path / "absent.obj"
    df = cohort.shape([missing, OPEN_MESH], domain="hemisphere")
    row = df[df["file"] == str(missing)].iloc[0]
    assert row["status"] == "failed" and str(missing) in row["error"] and pd.isna(row["bytes"])
    ok = df[df["file"] == str(OPEN_MESH)].iloc[0]
    assert ok["status"] == "ok" and ok["z_star"] == pytest.approx(0.0, abs=1e-12)


def test_missing_pandas_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(ImportError, match=r"python\[cohort\]"):
        cohort.shape([OPEN_MESH])


@pytest.fixture(scope="module")
def client():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, Client(cluster) as c:
        yield c


def test_local_cluster_equals_serial(client, cohort_dir, serial):
    assert len(client.scheduler_info()["workers"]) == 2
    pd.testing.assert_frame_equal(cohort.shape([cohort_dir], client=client), serial)


class KillOnce(WorkerPlugin):
    """Kills its worker process the first time a capmesh task starts executing there (the
    marker file makes it once for the whole cluster: the plugin is installed again on the
    worker the nanny starts in place of the dead one)."""

    def __init__(self, marker):
        self.marker = marker

    def transition(self, key, start, finish, **kwargs):
        if finish == "executing" and "capmesh-shape" in str(key) and not os.path.exists(self.marker):
            with open(self.marker, "w") as f:
                f.write(f"{key} {os.getpid()}\n")
            os._exit(1)


def test_a_worker_killed_during_the_cohort_loses_no_mesh(client, cohort_dir, serial, tmp_path):
    before = set(client.run(os.getpid).values())
    marker = tmp_path / "killed"
    cloudpickle.register_pickle_by_value(sys.modules[__name__])
    client.register_plugin(KillOnce(str(marker)), name="kill-once")
    try:
        df = cohort.shape([cohort_dir], client=client)
    finally:
        client.unregister_worker_plugin("kill-once")
        cloudpickle.unregister_pickle_by_value(sys.modules[__name__])
    key, pid = marker.read_text().split()
    assert key.startswith("capmesh-shape-") and int(pid) in before  # a worker did die mid-task
    pd.testing.assert_frame_equal(df, serial)
    client.wait_for_workers(2, timeout=60)
    assert int(pid) not in set(client.run(os.getpid).values())
