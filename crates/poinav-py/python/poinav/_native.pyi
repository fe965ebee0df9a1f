"""Type stubs of the native module (crates/poinav-py/src)."""

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, "os.PathLike[str]"]

class PoinavError(Exception):
    """Any error of poinav: bad input, an output that cannot be written."""

class IfcError(PoinavError):
    """An IFC file that cannot be read."""

    file: str
    line: Optional[int]
    entity_id: Optional[int]
    kind: str

class NoRouteError(PoinavError):
    """No route: unreachable for the robot, or no room for it."""

class Model:
    """An IFC model read by poinav; immutable, shareable between threads."""

    @property
    def file(self) -> str: ...
    @property
    def schema(self) -> str: ...
    @property
    def storeys(self) -> List[Dict[str, Any]]: ...
    @property
    def doors(self) -> List[Dict[str, Any]]: ...
    def __len__(self) -> int: ...
    def inspect(self) -> Dict[str, Any]: ...
    def count(self, cls: str) -> int: ...
    def psets(self, cls: str = "IfcProduct") -> Dict[str, Dict[str, Dict[str, Any]]]: ...
    def meshes(self, spaces: bool = False) -> List[Dict[str, Any]]: ...
    def mesh_failures(self) -> List[Dict[str, Any]]: ...
    def enrich(
        self,
        profiles: Sequence[_Path] = ...,
        rules: Optional[_Path] = None,
        pset_prefix: str = "Pset_",
    ) -> Enrichment: ...
    def building(self, profile: Optional[_Path] = None) -> Building: ...

class Enrichment:
    """A model classified with the POI rules for robot profiles."""

    @property
    def summary(self) -> Dict[str, Any]: ...
    @property
    def profiles(self) -> List[str]: ...
    def csv_bytes(self) -> bytes: ...
    def to_dataframe(self) -> Any: ...
    def write(
        self, path: _Path, csv: Optional[_Path] = None, ids: Optional[_Path] = None
    ) -> Dict[str, Any]: ...

class Grid:
    """A storey's occupancy grid (0 free, 1 occupied, 2 unknown; row 0 lowest y)."""

    FREE: int
    OCCUPIED: int
    UNKNOWN: int
    storey: str
    cells: npt.NDArray[np.uint8]
    clearance_m: npt.NDArray[np.float32]
    resolution: float
    origin: Tuple[float, float]
    @property
    def shape(self) -> Tuple[int, int]: ...
    def __array__(self, dtype: Any = None, copy: Optional[bool] = None) -> npt.NDArray[Any]: ...

class Building:
    """A model's storeys as navigation floors for one robot profile."""

    @property
    def profile(self) -> str: ...
    @property
    def storeys(self) -> List[Dict[str, Any]]: ...
    @property
    def connections(self) -> List[Dict[str, Any]]: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def meshed(self) -> int: ...
    @property
    def navigators_built(self) -> int: ...
    def grid(
        self,
        storey: Union[int, str],
        resolution: float = 0.05,
        furniture: str = "obstacle",
        pending_closed: bool = False,
    ) -> Grid: ...
    def route(
        self,
        a: str,
        b: str,
        resolution: float = 0.05,
        furniture: str = "obstacle",
        pending_closed: bool = False,
    ) -> Dict[str, Any]: ...
    def audit(
        self,
        profiles: Sequence[_Path] = ...,
        start: Optional[str] = None,
        resolution: float = 0.05,
        furniture: str = "obstacle",
        pending_closed: bool = False,
    ) -> Dict[str, Any]: ...

def open_path(path: _Path) -> Model: ...
def open_bytes(data: bytes, name: str = "<bytes>") -> Model: ...
def simulate(
    scenario: str,
    variant: Optional[str] = None,
    text: bool = False,
    base: Optional[_Path] = None,
    output: Optional[_Path] = None,
    trace: bool = True,
    stream: bool = False,
) -> Dict[str, Any]: ...
def read_trace(path: _Path) -> Dict[str, Any]: ...
def bench_psets(path: _Path, once: bool = False) -> int: ...
def bench_meshes(path: _Path) -> int: ...
