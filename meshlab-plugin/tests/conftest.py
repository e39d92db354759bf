"""Fixtures of the plugin tests: the plugin loaded once into PyMeshLab, and real meshes from the
repository's tests/data decompressed into a temporary directory."""
import gzip
import os
import pathlib
import shutil

import pymeshlab
import pytest

HERE = pathlib.Path(__file__).resolve().parent
DATA = HERE.parent.parent / "tests" / "data"
PLUGIN = pathlib.Path(
    os.environ.get("CAPMESH_MESHLAB_PLUGIN", HERE.parent / "build" / "libfilter_capmesh.so"))


@pytest.fixture(scope="session")
def plugin():
    """Loads libfilter_capmesh.so (built by build.sh) once; a missing file is a failure."""
    assert PLUGIN.is_file(), f"{PLUGIN} is missing: run meshlab-plugin/build.sh first"
    pymeshlab.load_plugin(str(PLUGIN))
    return PLUGIN


@pytest.fixture(scope="session")
def mesh_file(tmp_path_factory):
    """Returns a function: name of a tests/data/*.obj.gz -> path of the decompressed .obj."""
    root = tmp_path_factory.mktemp("meshes")

    def unpack(name):
        target = root / name.removesuffix(".gz")
        if not target.exists():
            with gzip.open(DATA / name, "rb") as src, open(target, "wb") as dst:
                shutil.copyfileobj(src, dst)
        return str(target)

    return unpack
