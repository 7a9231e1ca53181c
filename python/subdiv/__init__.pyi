"""Type stubs of the subdiv package."""

from os import PathLike
from typing import Literal, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt
import scipy.sparse

__version__: str

TriangleScheme = Literal["midpoint", "loop", "butterfly", "modified-butterfly", "jarek"]
PolygonScheme = Literal["catmull-clark", "bilinear"]
Scheme = Union[TriangleScheme, PolygonScheme]
Beta = Literal["loop", "warren"]
Boundary = Literal["edge", "edge-and-corner", "none"]
Fvar = Literal["none", "corners-only", "corners-plus1", "corners-plus2", "boundaries", "all"]
Triangles = Literal["catmark", "smooth"]
Creasing = Literal["uniform", "chaikin"]
Shading = Literal["phong", "flat", "studio", "wire", "phong+wire"]
Faces = Union[npt.ArrayLike, Sequence[Sequence[int]]]
Creases = tuple[npt.ArrayLike, npt.ArrayLike] | None
Holes = npt.ArrayLike | None
Path = Union[str, PathLike[str]]

TRIANGLE_SCHEMES: tuple[str, ...]
POLYGON_SCHEMES: tuple[str, ...]

class SubdivError(ValueError): ...

class FileResult(TypedDict):
    """What :func:`subdivide_file` did (a line of ``subdiv batch``'s manifest)."""

    input: str
    output: str
    status: Literal["done"]
    scheme: str
    levels: int
    input_vertices: int
    input_faces: int
    vertices: int
    faces: int
    output_bytes: int | None
    seconds: float

class Prim:
    path: str
    options: dict[str, str]
    faces: npt.NDArray[np.int64]
    transform: npt.NDArray[np.float64]
    def __init__(self, path: str, options: dict[str, str], faces: npt.ArrayLike, transform: npt.ArrayLike) -> None: ...

class Mesh:
    vertices: npt.NDArray[np.float64]
    faces: npt.NDArray[np.int64]
    uv: npt.NDArray[np.float64] | None
    colors: npt.NDArray[np.float64] | None
    polygons: npt.NDArray[np.int64] | list[npt.NDArray[np.int64]] | None
    options: dict[str, str]
    prims: list[Prim]
    def __init__(
        self,
        vertices: npt.NDArray[np.float64],
        faces: npt.NDArray[np.int64],
        uv: npt.NDArray[np.float64] | None = ...,
        colors: npt.NDArray[np.float64] | None = ...,
        polygons: npt.NDArray[np.int64] | list[npt.NDArray[np.int64]] | None = ...,
        options: dict[str, str] | None = ...,
        prims: list[Prim] = ...,
    ) -> None: ...

class Refiner:
    def __init__(
        self,
        vertices: npt.ArrayLike,
        faces: Faces,
        levels: int = 1,
        scheme: str = "loop",
        *,
        beta: Beta = "loop",
        boundary: Boundary = "edge",
        fvar: Fvar = "corners-only",
        triangles: Triangles = "catmark",
        creasing: Creasing = "uniform",
        creases: Creases = None,
        holes: Holes = None,
        threads: int | None = None,
    ) -> None: ...
    @property
    def vertices(self) -> npt.NDArray[np.floating]: ...
    @property
    def faces(self) -> npt.NDArray[np.int64]: ...
    def move(self, ids: npt.ArrayLike, positions: npt.ArrayLike) -> npt.NDArray[np.int64]: ...
    def set_sharpness(self, v0: int, v1: int, sharpness: float) -> npt.NDArray[np.int64]: ...
    def undo(self) -> bool: ...
    def redo(self) -> bool: ...
    def support(self, vertex: int) -> npt.NDArray[np.int64]: ...

def subdivide(
    vertices: npt.ArrayLike,
    faces: Faces,
    levels: int = 1,
    scheme: Scheme = "loop",
    *,
    beta: Beta = "loop",
    boundary: Boundary = "edge",
    fvar: Fvar = "corners-only",
    triangles: Triangles = "catmark",
    creasing: Creasing = "uniform",
    creases: Creases = None,
    holes: Holes = None,
    repair: bool = False,
    threads: int | None = None,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...
def matrix(
    faces: Faces,
    levels: int = 1,
    scheme: Scheme = "loop",
    *,
    n_vertices: int | None = None,
    beta: Beta = "loop",
    boundary: Boundary = "edge",
    triangles: Triangles = "catmark",
    creasing: Creasing = "uniform",
    creases: Creases = None,
    holes: Holes = None,
    return_faces: bool = False,
    threads: int | None = None,
) -> scipy.sparse.csr_matrix | tuple[scipy.sparse.csr_matrix, npt.NDArray[np.int64]]: ...
def evaluate(
    vertices: npt.ArrayLike,
    faces: npt.ArrayLike,
    face: npt.ArrayLike,
    uv: npt.ArrayLike,
    *,
    scheme: str = "loop",
    beta: Beta = "loop",
    boundary: Boundary = "edge",
    triangles: Triangles = "catmark",
    creasing: Creasing = "uniform",
    creases: Creases = None,
    curvature: bool = False,
    threads: int | None = None,
) -> (
    tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]
    | tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]
): ...
def limit(
    vertices: npt.ArrayLike,
    faces: npt.ArrayLike,
    *,
    beta: Beta = "loop",
    boundary: Boundary = "edge",
    creases: Creases = None,
    threads: int | None = None,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
def tessellate(
    vertices: npt.ArrayLike,
    faces: Faces,
    tolerance: float | str = "1e-4x",
    *,
    scheme: str = "loop",
    beta: Beta = "loop",
    boundary: Boundary = "edge",
    triangles: Triangles = "catmark",
    creasing: Creasing = "uniform",
    creases: Creases = None,
    threads: int | None = None,
) -> tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.int64],
    npt.NDArray[np.float64],
    npt.NDArray[np.int64],
    npt.NDArray[np.float64],
]: ...
def load(path: Path, *, repair: bool = False, time: float | None = None, threads: int | None = None) -> Mesh: ...
def save(path: Path, vertices: npt.ArrayLike, faces: Faces, *, threads: int | None = None) -> None: ...
def subdivide_file(
    input: Path,
    output: Path,
    levels: int = 1,
    scheme: Scheme | None = None,
    *,
    beta: Beta = "loop",
    boundary: Boundary | None = None,
    fvar: Fvar | None = None,
    triangles: Triangles | None = None,
    creasing: Creasing | None = None,
    repair: bool = False,
    precision: Literal["f32", "f64"] = "f32",
    time: float | None = None,
    threads: int | None = None,
) -> FileResult: ...
def render(
    vertices: npt.ArrayLike,
    faces: Faces,
    *,
    size: tuple[int, int] = (640, 480),
    shading: Shading = "phong",
    levels: int = 0,
    scheme: Scheme = "loop",
    beta: Beta = "loop",
    boundary: Boundary = "edge",
    creases: Creases = None,
) -> npt.NDArray[np.uint8]: ...
def view(
    vertices: npt.ArrayLike,
    faces: Faces,
    *,
    levels: int = 0,
    scheme: Scheme = "loop",
    beta: Beta = "loop",
    boundary: Boundary = "edge",
    wireframe: bool = False,
    control: bool = False,
    frames: int | None = None,
    screenshot: Path | None = None,
) -> None: ...
