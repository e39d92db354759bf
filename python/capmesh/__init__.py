"""capmesh: adaptive area-preserving parameterization of anatomical surfaces onto a spherical
cap, and remeshing through it (Python bindings of the Rust library; see python/README.md).

Meshes are numpy arrays: vertices ``(n, 3)`` float32 or float64, faces ``(m, 3)`` int32, int64
or uint32 (0-based). Options are named as the CLI's flags (``--open-lambda`` ->
``open_lambda``; ``--lambda`` -> ``lambda_``). Errors raise subclasses of
:class:`CapmeshError` with the CLI's messages. Every computation releases the GIL.
:meth:`CapMap.inverse` maps cap points back to the surface; :mod:`capmesh.cohort` runs the
shape analysis of ``capmesh shape`` over a cohort, serially or on Dask (docs/python.md).
"""

import json as _json
from typing import Any, Callable, Dict, NamedTuple, Optional, Tuple

import numpy as _np

from . import _capmesh, cohort  # noqa: F401  (cohort imports pandas and dask only when used)
from ._capmesh import (  # noqa: F401  (re-exported)
    CapmeshError,
    Cancelled,
    ComputeError,
    InputError,
    InternalError,
    MeshError,
    ReadError,
    WriteError,
)

__all__ = [
    "CapMap", "InversePoints", "cohort", "parameterize", "remesh", "harmonics", "metrics", "read_mesh", "write_mesh",
    "CapmeshError", "Cancelled", "ComputeError", "InputError", "InternalError", "MeshError",
    "ReadError", "WriteError",
]

_FLOATS = (_np.float32, _np.float64)
_INDICES = (_np.int32, _np.int64, _np.uint32)


def _vertices(v):
    """Arrays of an accepted dtype pass through untouched; anything else (lists, other
    dtypes) is converted to float64 once."""
    if isinstance(v, _np.ndarray) and v.dtype in _FLOATS:
        return v
    return _np.asarray(v, dtype=_np.float64)


def _faces(f):
    if isinstance(f, _np.ndarray) and f.dtype in _INDICES:
        return f
    a = _np.asarray(f)
    if a.dtype.kind not in "iu":
        raise InputError(f"faces must hold integer vertex indices, not {a.dtype}")
    return a.astype(_np.int64, copy=False)


class InversePoints(NamedTuple):
    """The surface points of :meth:`CapMap.inverse`, one row per cap point asked for. A point
    off the cap has face ``-1`` and NaN position and barycentric coordinates."""

    points: _np.ndarray
    """(k, 3) float64: positions on the input surface."""
    faces: _np.ndarray
    """(k,) int64: the input face each point lies in (``-1``: off the cap)."""
    barycentric: _np.ndarray
    """(k, 3) float64: weights of the face's three corners, in the order of ``faces[face]``
    of the input (non-negative, sum 1)."""


class CapMap:
    """A parameterization: ``cap`` (n, 3) points on the unit sphere with ``Z >= z_star``
    (``(x, y, 0)`` for the planar disk), ``plane`` (n, 2) points on the disk of radius
    ``r_star``, one per input vertex; ``report`` the library's report as a dict (the CLI's
    ``param --report`` JSON). A map made by :func:`parameterize` also keeps its mesh for
    :meth:`inverse`."""

    def __init__(self, cap: _np.ndarray, plane: _np.ndarray, report: Dict[str, Any]):
        self.cap = cap
        self.plane = plane
        self.report = report
        self._native = None

    def inverse(self, points, tolerance: float = 1e-9) -> InversePoints:
        """Where on the input surface the cap points ``points`` lie: the inverse map
        ``f^-1`` (paper Sec. 4.2, the library's ``CapMap::inverse``).

        ``points`` is a ``(k, 3)`` array (or one point of shape ``(3,)``, answered as
        ``k = 1``) of points on the cap: on the unit sphere with ``Z >= z_star``, a closed
        surface's flat bottom disk ``Z = z_star`` included; ``(x, y, 0)`` in the disk for
        ``domain="disk"``. Returns :class:`InversePoints` ``(points, faces, barycentric)``;
        a point farther than ``tolerance`` off the cap, or not finite, gets face ``-1`` and
        NaN, it is never guessed. Each call builds the point location over the input's faces
        once and locates the points in parallel with the GIL released: pass many points in
        one call rather than one call per point."""
        if self._native is None:
            raise InputError("this CapMap was not made by capmesh.parameterize (it has no mesh to map back to); "
                             "call capmesh.parameterize(vertices, faces) and use its result")
        p = _np.asarray(points, dtype=_np.float64)
        if p.ndim == 1 and p.shape == (3,):
            p = p.reshape(1, 3)
        if p.ndim != 2 or p.shape[1] != 3:
            raise InputError(f"points must have shape (k, 3), not {p.shape}: one row (X, Y, Z) per cap point")
        return InversePoints(*self._native.inverse(p, float(tolerance)))

    @property
    def z_star(self) -> Optional[float]:
        """The cap's height ``Z*`` (None for the planar disk)."""
        return self.report.get("z_star")

    @property
    def r_star(self) -> Optional[float]:
        """The disk radius ``r*`` (None for the planar disk)."""
        return self.report.get("r_star")

    def __repr__(self) -> str:
        return f"CapMap(n={len(self.cap)}, z_star={self.z_star}, r_star={self.r_star})"


ProgressCallback = Callable[[str, float, str], Optional[bool]]


def parameterize(vertices, faces, domain: str = "adaptive", progress: Optional[ProgressCallback] = None, **options) -> CapMap:
    """Map an open disk-like or closed genus-0 surface onto ``domain`` (``"adaptive"``,
    ``"disk"``, ``"hemisphere"``, ``"sphere"`` or ``"radius=R"``), as ``capmesh param``.

    ``progress(stage, fraction, message)`` is called now and then on the calling thread;
    returning ``False`` cancels (raises :class:`Cancelled`), raising cancels with that
    exception. Options: initial, lambda_, open_lambda, no_lambda_fallback, smoothing,
    area_refinement, puncture_end, search_sites, multilevel_above, coarse_vertices (see
    ``capmesh param --help``)."""
    native, report = _capmesh.parameterize(_vertices(vertices), _faces(faces), domain, progress, **options)
    m = CapMap(native.cap(), native.plane(), _json.loads(report))
    m._native = native
    return m


def remesh(vertices, faces, faces_target: int = 5000, lat_long: Optional[Tuple[int, int]] = None,
           progress: Optional[ProgressCallback] = None, **options) -> Tuple[_np.ndarray, _np.ndarray, Dict[str, Any]]:
    """Remesh through the adaptive cap, as ``capmesh remesh``: about ``faces_target`` faces
    (``--faces``), or a latitude/longitude grid of ``lat_long = (rings, sectors)``. Returns
    ``(vertices, faces, report)``. Options: those of :func:`parameterize` and
    area_equalization, optimize, relax_iterations, polish_iterations, polish_tolerance, area_steps,
    shape_weight, no_resample, sizing ("uniform", the default, "surface" or "curvature[=S]"),
    creases ("auto", the default: kept with curvature sizing, "keep" or "off": ``--creases``),
    keep_creases (``--keep-creases``: True is creases="keep"), crease_angle (``--crease-angle``,
    degrees, default 60), placement ("fitted", the default, or
    "on-surface": ``--placement``), fill_holes (``--fill-holes``, default False), no_subdivide
    (``--no-subdivide``, default False: an input with fewer faces than asked is mapped subdivided),
    fine_map (``--fine-map``, default False: with the shape stage, a closed input of many more
    vertices than the remesh needs is mapped through a decimated copy sized to the remesh)."""
    v, f, report = _capmesh.remesh(_vertices(vertices), _faces(faces), faces_target, lat_long, progress, **options)
    return v, f, _json.loads(report)


def harmonics(vertices, faces, order: int = 10, domain: str = "adaptive", progress: Optional[ProgressCallback] = None,
              **options) -> Tuple[_np.ndarray, _np.ndarray, Dict[str, Any]]:
    """Adaptive harmonics up to ``order``, as ``capmesh harmonics``: returns the reconstructed
    vertices (the input's connectivity), the ``(order + 1)**2`` coefficients ``(x, y, z)`` in
    the library's basis order, and the report (``--report``) as a dict. Options: those of
    :func:`parameterize`."""
    v, c, report = _capmesh.harmonics(_vertices(vertices), _faces(faces), order, domain, progress, **options)
    return v, c, _json.loads(report)


def metrics(original: Tuple[Any, Any], remeshed: Tuple[Any, Any]) -> Dict[str, Any]:
    """Quality of ``remeshed = (vertices, faces)`` against ``original``, as
    ``capmesh metrics --json``."""
    (v0, f0), (v1, f1) = original, remeshed
    return _json.loads(_capmesh.metrics(_vertices(v0), _faces(f0), _vertices(v1), _faces(f1)))


def read_mesh(path) -> Tuple[_np.ndarray, _np.ndarray]:
    """Read OBJ, OFF, PLY, STL, GIFTI or FreeSurfer surface (optionally gzipped) as
    ``(vertices float64 (n, 3), faces int64 (m, 3))``."""
    return _capmesh.read_mesh(str(path))


def write_mesh(path, vertices, faces) -> None:
    """Write a mesh; the format follows the extension, as in the CLI."""
    _capmesh.write_mesh(str(path), _vertices(vertices), _faces(faces))
