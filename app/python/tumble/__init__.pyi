# Type stubs of the tumble package (docs/python.md). SI units throughout: metres, kilograms,
# seconds, radians. Quaternions are (w, x, y, z); principal axes are the COLUMNS of a rotation.
import os
from typing import Any, Literal, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

PathLike = Union[str, os.PathLike[str]]
Float = npt.NDArray[np.float64]

__version__: str

class InputError(ValueError):
    """Bad input; str() is the command line's one-line message, file the file it names."""
    file: Optional[str]

class RunBlewUp(RuntimeError):
    output: Any

class MassProperties:
    volume: float  # m^3
    mass: float  # kg
    density: float  # kg/m^3
    center_of_mass: Float  # (3,) m
    inertia: Float  # (3, 3) kg m^2 about the centre of mass
    principal_moments: Float  # (3,) kg m^2, ascending
    principal_axes: Float  # (3, 3), the principal axes as columns, det +1
    principal_quaternion: Float  # (4,) w, x, y, z of principal_axes
    bounds: tuple[Float, Float]  # the corners (3,), (3,) of the axis-aligned box, m
    warnings: list[str]
    method: str  # "exact", "shell" or "closed form"
    source: str
    def inertia_about(self, point: npt.ArrayLike) -> Float: ...  # (3, 3) about a point (3,)
    def to_dict(self) -> dict[str, Any]: ...  # `tumble inspect --json`'s object
    def to_xml(self, format: Literal["urdf", "sdf", "mjcf"],
               frame: Literal["mesh", "principal"] = "mesh") -> str: ...

def inspect(path: PathLike, *, density: Optional[float] = None, mass: Optional[float] = None,
            scale: Union[float, Sequence[float]] = 1.0, shell: Optional[float] = None,
            inertia: Literal["exact", "shell"] = "exact",
            allow_overlap: bool = False) -> MassProperties: ...
def mass_properties(vertices: npt.ArrayLike, faces: npt.ArrayLike, *,
                    density: Optional[float] = None, mass: Optional[float] = None,
                    scale: Union[float, Sequence[float]] = 1.0, shell: Optional[float] = None,
                    inertia: Literal["exact", "shell"] = "exact",
                    allow_overlap: bool = False) -> MassProperties: ...
def primitive(kind: Literal["box", "sphere", "cylinder", "capsule", "ellipsoid", "cone"], *,
              density: Optional[float] = None, mass: Optional[float] = None,
              **dimensions: Union[float, Sequence[float]]) -> MassProperties: ...

class RobotInertials:
    file: str
    format: Literal["urdf", "sdf", "mjcf"]
    geometry: Literal["collision", "visual"]
    links: list[dict[str, Any]]  # `tumble inertials --json`'s "links"
    errors: list[str]  # one line per link whose geometry failed
    total: Optional[dict[str, Any]]  # the whole robot, zero configuration (--json's "total")
    def failing(self, tolerance: float = 1e-3) -> list[str]: ...
    def to_dict(self, tolerance: Optional[float] = None) -> dict[str, Any]: ...
    def write(self, path: PathLike, *, frame: Literal["mesh", "principal"] = "mesh") -> str: ...

def inertials(robot: PathLike, *, geometry: Literal["collision", "visual"] = "collision",
              density: Optional[float] = None, package_paths: Mapping[str, PathLike] = ...,
              allow_overlap: bool = False, inertia: str = "exact",
              densities: Mapping[str, float] = ..., masses: Mapping[str, float] = ...,
              total_mass: Optional[float] = None) -> RobotInertials: ...

class Trajectory:
    t: Float  # (N,) s
    position: Float  # (N, B, 3) m, centre of mass, world
    orientation: Float  # (N, B, 4) w, x, y, z: the scene's body frame in the world
    velocity: Float  # (N, B, 3) m/s
    angular_velocity: Float  # (N, B, 3) rad/s, world
    angular_momentum: Float  # (N, B, 3) kg m^2/s, world, about the rotation centre
    body_energy: Float  # (N, B) J
    energy: Float  # (N,) J, summed over the bodies
    body_names: list[str]
    summary: dict[str, Any]  # `tumble simulate --json`'s object
    blew_up: bool
    blow_up: Optional[str]
    def to_csv(self, path: PathLike) -> None: ...
    def __len__(self) -> int: ...

def simulate(scene: Union[PathLike, Mapping[str, Any]], *, integrator: Optional[str] = None,
             dt: Optional[float] = None, duration: Optional[float] = None,
             tolerance: Optional[float] = None,
             absolute_tolerance: Optional[float] = None, every: int = 1,
             blowup_factor: Optional[float] = None, allow_long: bool = False) -> Trajectory: ...
def integrators() -> list[dict[str, Any]]: ...

def executable() -> str: ...
def render(scene: Union[PathLike, Mapping[str, Any]], output: PathLike,
           **options: Any) -> os.PathLike[str]: ...
def compare(scene: Union[PathLike, Mapping[str, Any]], output: PathLike,
            integrators: Sequence[str], **options: Any) -> os.PathLike[str]: ...
def bench(scenes: Sequence[Union[PathLike, Mapping[str, Any]]], *,
          integrators: Optional[Sequence[str]] = None, dts: Optional[Sequence[float]] = None,
          tolerances: Optional[Sequence[float]] = None, duration: Optional[float] = None,
          repeat: Optional[int] = None, jobs: Optional[int] = None) -> list[dict[str, Any]]: ...
def stability(scenes: Sequence[Union[PathLike, Mapping[str, Any]]] = (), *,
              suite: Optional[Literal["standard", "quick"]] = None,
              integrators: Optional[Sequence[str]] = None, cases: Optional[Sequence[str]] = None,
              dts: Optional[Sequence[float]] = None) -> list[dict[str, Any]]: ...
