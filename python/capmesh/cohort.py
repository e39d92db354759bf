"""capmesh.cohort: the shape analysis of ``capmesh shape`` over a cohort of mesh files, as a
pandas DataFrame, on this machine or on a Dask cluster (see docs/python.md).

Each mesh is analysed on its own, on one thread (the library's order-1 harmonics fit, paper
Sec. "Shape analysis of demented and non-demented cortical surfaces": ``Z*`` and the aspect
ratio ``sigma1 / sigma3``), so a row does not depend on where it ran: the serial run, a local
cluster and a SLURM cluster give the same DataFrame, with the columns and values of the CLI's
CSV. On a cluster each mesh is one task and the workers read their own files (the paths must
be valid on the workers). A mesh that cannot be read or analysed is a row with ``status =
"failed"`` and the error's text, never an exception. A task whose worker dies (killed, out of
memory) is run again by the Dask scheduler on another worker, up to
``distributed.scheduler.allowed-failures`` times (Dask's default: 3); a task that raised is
run again up to ``retries`` times; a mesh that still has no result is a failed row saying so.

pandas (and, for a cluster, ``dask[distributed]``) are optional dependencies:
``pip install './python[cohort]'``.
"""

import hashlib
import os
import uuid
from typing import Any, Dict, Iterable, List, Optional, Union

from . import _capmesh
from ._capmesh import InputError

__all__ = ["COLUMNS", "mesh_files", "shape"]

PathLike = Union[str, "os.PathLike[str]"]

#: The columns of ``capmesh shape``'s CSV, in order.
COLUMNS = [
    "file", "status", "quality", "vertices", "faces", "kind", "z_star", "aspect_ratio",
    "ellipsoid_aspect_ratio", "sigma1", "sigma2", "sigma3", "mean_abs_area_distortion", "lambda",
    "error", "bytes", "modified", "sha256",
]
_INTEGERS = ["vertices", "faces", "bytes"]
_FLOATS = ["z_star", "aspect_ratio", "ellipsoid_aspect_ratio", "sigma1", "sigma2", "sigma3",
           "mean_abs_area_distortion", "lambda"]
_EXTRA = "pip install './python[cohort]' (from the capmesh repository) or pip install pandas 'dask[distributed]'"


def _pandas():
    try:
        import pandas
    except ImportError as e:
        raise ImportError(f"capmesh.cohort.shape returns a pandas DataFrame and needs pandas: {_EXTRA}") from e
    return pandas


def mesh_files(paths: Iterable[PathLike]) -> List[str]:
    """The mesh files of ``paths`` as ``capmesh shape`` collects them: files as given,
    directories searched recursively for the formats capmesh reads (symbolic links to
    directories not followed, the temporaries of capmesh's atomic writes skipped); sorted,
    each once."""
    if isinstance(paths, (str, bytes, os.PathLike)):
        paths = [paths]
    files = []
    for p in paths:
        p = os.fspath(p)
        if os.path.isdir(p):
            for root, dirs, names in os.walk(p):
                dirs.sort()
                for name in names:
                    full = os.path.join(root, name)
                    if os.path.isfile(full) and _capmesh.is_mesh_path(full):
                        files.append(full)
        else:
            files.append(p)
    return sorted(set(files))


def _identity(path: str) -> Dict[str, Any]:
    """The CSV's ``bytes``, ``modified`` (seconds.nanoseconds since 1970) and ``sha256`` of the
    file as it is about to be read; None where it cannot be read."""
    out: Dict[str, Any] = {"bytes": None, "modified": None, "sha256": None}
    try:
        st = os.stat(path)
        out["bytes"] = st.st_size
        if st.st_mtime_ns >= 0:
            out["modified"] = f"{st.st_mtime_ns // 10**9}.{st.st_mtime_ns % 10**9:09d}"
        digest = hashlib.sha256()
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                digest.update(block)
        out["sha256"] = digest.hexdigest()
    except OSError:
        pass
    return out


def _failed(path: str, error: str) -> Dict[str, Any]:
    row = dict.fromkeys(COLUMNS)
    row.update(file=path, status="failed", error=error.replace("\n", " ").replace("\r", " "))
    return row


def _row(path: str, domain: str, basis: str, boundary: str) -> Dict[str, Any]:
    """One mesh's row (run on a worker): never raises for a bad mesh."""
    identity = _identity(path)
    try:
        values = _capmesh.shape_row(path, domain, basis, boundary)
    except (KeyboardInterrupt, SystemExit):
        raise
    except BaseException as e:  # a bug surfacing as an exception still gives a row
        values = {"status": "failed", "error": f"{type(e).__name__}: {e}".replace("\n", " ")}
    row = dict.fromkeys(COLUMNS)
    row.update(values)
    row.update(identity)
    row["file"] = path
    return row


def _frame(rows: List[Dict[str, Any]]):
    pd = _pandas()
    df = pd.DataFrame(rows, columns=COLUMNS)
    for c in _INTEGERS:
        df[c] = df[c].astype("Int64")
    for c in _FLOATS:
        df[c] = df[c].astype("float64")
    return df.sort_values("file", kind="stable").reset_index(drop=True)


def shape(paths: Iterable[PathLike], client: Optional[Any] = None, *, domain: str = "adaptive", basis: str = "ah",
          boundary: str = "neumann", retries: int = 1):
    """The shape analysis of ``capmesh shape`` of each mesh file in ``paths`` (files, or
    directories searched recursively as by :func:`mesh_files`), as a pandas DataFrame with
    one row per mesh, sorted by file, and the CLI's CSV columns (:data:`COLUMNS`).

    Options are the CLI's: ``domain`` (``"adaptive"``, ``"hemisphere"``, ``"sphere"``,
    ``"radius=R"``), ``basis`` (``"ah"`` or ``"scha"``), ``boundary`` (``"neumann"``,
    ``"dirichlet"``, ``"mixed"``; with ``basis="scha"`` only). Bad options raise
    :class:`capmesh.InputError` before any mesh is read; no mesh file in ``paths`` too.

    Without ``client`` the meshes run here, one after the other. With a
    ``dask.distributed.Client`` each mesh is one task on its cluster (give the workers one
    thread each: a mesh uses one thread, and more threads per worker only share the
    worker's memory); the workers read the files themselves. ``retries`` is Dask's
    ``retries=`` for a task that raised; a task lost with its worker is run again by the
    scheduler (``distributed.scheduler.allowed-failures``).

    Columns: ``status`` (``ok`` or ``failed``) and ``error`` as in the CLI's CSV; the
    numbers as float64 (NaN where the CSV has an empty field), ``vertices``, ``faces`` and
    ``bytes`` as pandas' nullable ``Int64``; ``modified`` as the CLI's text (seconds and
    nanoseconds since 1970, exact). Requires pandas (``pip install './python[cohort]'``)."""
    _pandas()
    _capmesh.check_shape_options(domain, basis, boundary)
    files = mesh_files(paths)
    if not files:
        raise InputError("no mesh files (.obj, .ply, .off, .stl, .gii, lh.pial, ..., optionally .gz) in the given paths")
    if client is None:
        return _frame([_row(f, domain, basis, boundary) for f in files])
    return _frame(_on_cluster(client, files, domain, basis, boundary, retries))


def _on_cluster(client, files: List[str], domain: str, basis: str, boundary: str, retries: int) -> List[Dict[str, Any]]:
    try:
        import distributed  # noqa: F401  (the client's package: its futures are awaited here)
    except ImportError as e:
        raise ImportError(f"capmesh.cohort.shape with a client needs dask.distributed: {_EXTRA}") from e
    run = uuid.uuid4().hex
    keys = [f"capmesh-shape-{run}-{i}" for i in range(len(files))]
    futures = client.map(_row, files, domain=domain, basis=basis, boundary=boundary, key=keys, retries=retries, pure=False)
    rows = []
    try:
        for file, future in zip(files, futures):
            try:
                rows.append(future.result())
            except Exception as e:  # KilledWorker (the worker died on every try), a cancelled task
                rows.append(_failed(file, f"no result from the cluster: {type(e).__name__}: {e}"))
    except BaseException:
        client.cancel(futures)
        raise
    return rows
