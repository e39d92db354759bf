import os
from typing import Any, Iterable, List, Optional, Union

import pandas

PathLike = Union[str, "os.PathLike[str]"]

COLUMNS: List[str]

def mesh_files(paths: Union[PathLike, Iterable[PathLike]]) -> List[str]: ...
def shape(
    paths: Union[PathLike, Iterable[PathLike]],
    client: Optional[Any] = None,
    *,
    domain: str = "adaptive",
    basis: str = "ah",
    boundary: str = "neumann",
    retries: int = 1,
) -> pandas.DataFrame: ...
