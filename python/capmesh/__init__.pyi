from typing import Any, Callable, Dict, NamedTuple, Optional, Tuple, Union
import os
import numpy as np
import numpy.typing as npt

from . import cohort as cohort

ProgressCallback = Callable[[str, float, str], Optional[bool]]
Vertices = npt.ArrayLike
Faces = npt.ArrayLike
PathLike = Union[str, "os.PathLike[str]"]

class CapmeshError(Exception): ...
class InputError(CapmeshError): ...
class ReadError(CapmeshError): ...
class WriteError(CapmeshError): ...
class MeshError(CapmeshError): ...
class ComputeError(CapmeshError): ...
class InternalError(CapmeshError): ...
class Cancelled(CapmeshError): ...

class InversePoints(NamedTuple):
    points: npt.NDArray[np.float64]
    faces: npt.NDArray[np.int64]
    barycentric: npt.NDArray[np.float64]

class CapMap:
    cap: npt.NDArray[np.float64]
    plane: npt.NDArray[np.float64]
    report: Dict[str, Any]
    def __init__(self, cap: npt.NDArray[np.float64], plane: npt.NDArray[np.float64], report: Dict[str, Any]) -> None: ...
    @property
    def z_star(self) -> Optional[float]: ...
    @property
    def r_star(self) -> Optional[float]: ...
    def inverse(self, points: npt.ArrayLike, tolerance: float = 1e-9) -> InversePoints: ...

def parameterize(
    vertices: Vertices,
    faces: Faces,
    domain: str = "adaptive",
    progress: Optional[ProgressCallback] = None,
    *,
    initial: str = "composite",
    lambda_: float = 0.2,
    open_lambda: float = 0.5,
    no_lambda_fallback: bool = False,
    smoothing: Union[str, float] = "auto",
    area_refinement: int = 30,
    puncture_end: str = "best",
    search_sites: int = 2000,
    multilevel_above: int = 100000,
    coarse_vertices: int = 25000,
) -> CapMap: ...
def remesh(
    vertices: Vertices,
    faces: Faces,
    faces_target: int = 5000,
    lat_long: Optional[Tuple[int, int]] = None,
    progress: Optional[ProgressCallback] = None,
    **options: Any,
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], Dict[str, Any]]: ...
def harmonics(
    vertices: Vertices,
    faces: Faces,
    order: int = 10,
    domain: str = "adaptive",
    progress: Optional[ProgressCallback] = None,
    **options: Any,
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], Dict[str, Any]]: ...
def metrics(original: Tuple[Vertices, Faces], remeshed: Tuple[Vertices, Faces]) -> Dict[str, Any]: ...
def read_mesh(path: PathLike) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...
def write_mesh(path: PathLike, vertices: Vertices, faces: Faces) -> None: ...
