"""Shared fixtures: the repository's test meshes (tests/data) and the built CLI, whose results
the package must equal. The CLI is `$CAPMESH_CLI` or target/release/capmesh (built by
`cargo build --release`); a missing CLI fails the tests that need it, it does not skip them."""

import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
DATA = REPO / "tests" / "data"
OPEN_MESH = DATA / "open_meg_helmet_babysquid_mne.obj.gz"
CLOSED_MESH = DATA / "closed_bunny_npm.obj.gz"
GENUS2_MESH = DATA / "bad_genus2_bird_skull_choi.obj.gz"


def cli_path() -> pathlib.Path:
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    return pathlib.Path(os.environ.get("CAPMESH_CLI", target / "release" / "capmesh"))


@pytest.fixture(scope="session")
def cli():
    """Run the CLI; returns the CompletedProcess (text mode)."""
    path = cli_path()
    assert path.is_file(), f"{path} not found: build it with `cargo build --release` or set CAPMESH_CLI"

    def run(*args):
        return subprocess.run([str(path), *map(str, args)], capture_output=True, text=True)

    return run
