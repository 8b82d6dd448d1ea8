"""Type stubs of the extension module (checked with mypy.stubtest in CI)."""

from typing import Any, TypeAlias, final

import numpy as np
import numpy.typing as npt

__version__: str
BUILD_PROFILE: str
SINGULAR_THRESHOLD: float
STATUSES: list[tuple[int, str, str]]
SCENE_KEYS: list[str]
SCENE_REQUIRED: list[str]
SCENE_MAX_DEPTH: int
TOL: float
MAX_ITER: int
MAX_STEP: float
SEED: int
RUNS: int
TRACE_STEP: float
TRACE_MAX_POINTS: int
SWEEP_LEN: int
__all__ = [
    "ATLAS_DESCRIPTOR",
    "ATLAS_HARMONICS",
    "ATLAS_SAMPLES",
    "ATLAS_TOPOLOGIES",
    "BUILD_PROFILE",
    "MAX_ITER",
    "MAX_STEP",
    "RUNS",
    "SCENE_KEYS",
    "SCENE_MAX_DEPTH",
    "SCENE_REQUIRED",
    "SEED",
    "SWEEP_LEN",
    "TOL",
    "TRACE_MAX_POINTS",
    "TRACE_STEP",
    "ForceModel",
    "FourBar",
    "Plan",
    "Scene",
    "SINGULAR_THRESHOLD",
    "STATUSES",
    "__version__",
    "atlas_curve",
    "atlas_describe",
    "atlas_match",
    "atlas_match_curves",
    "atlas_pose",
    "atlas_shard",
    "closed_form_batch",
    "load_scene",
    "load_scene_json",
    "set_simd",
    "simd_available",
    "simd_enabled",
    "sweep_batch",
    "transmission",
]

_F64: TypeAlias = npt.NDArray[np.float64]

_Table: TypeAlias = tuple[list[float], list[float]]
_Element: TypeAlias = tuple[int, int, int, int, float, float, float]
_Run: TypeAlias = tuple[
    _F64, npt.NDArray[np.int8], _F64, _F64, _F64, _F64, _F64, _F64 | None, float, float | None
]

@final
class ForceModel:
    def __new__(
        cls,
        points: int,
        moving: int,
        size: float,
        refs: list[int],
        forces: list[tuple[int, int, float, int, int, int]],
        couples: list[tuple[int, int, float]],
        lines: list[tuple[int, int, int]],
        blocks: list[tuple[list[int], list[int], list[int]]],
        point_forces: list[tuple[int, int, _Table]],
        line_forces: list[tuple[int, int, int, _Table]],
        torques: list[tuple[int, _Table]],
        springs: list[_Element],
        dampers: list[_Element],
        gravity: tuple[float, float] | None,
        masses: list[tuple[int, int, int, tuple[float, float], tuple[float, float], float, float]],
        period: float | None,
        output: tuple[bool, int, int] | None,
    ) -> ForceModel: ...
    def run(
        self,
        theta: _F64,
        status: npt.NDArray[np.int8],
        det: _F64,
        coords: _F64,
        velocity: _F64,
        acceleration: _F64 | None,
        angular_velocity: _F64,
        angular_acceleration: _F64 | None,
        point_map: list[int],
        link_map: list[int],
        rate: float,
        omega: _F64 | None = None,
        alpha: _F64 | None = None,
    ) -> _Run: ...

@final
class FourBar:
    def __new__(cls, r1: float, r2: float, r3: float, r4: float) -> FourBar: ...
    @property
    def lengths(self) -> tuple[float, float, float, float]: ...
    def solve(
        self,
        theta2: float,
        mode: str,
        guess: tuple[float, float] | None,
        tol: float,
        max_iter: int,
        history: bool,
    ) -> tuple[float, float, int, int, float, _F64 | None]: ...
    def sweep(
        self,
        theta2: _F64,
        mode: str,
        guess: tuple[float, float] | None,
        tol: float,
        max_iter: int,
        predictor: str,
        method: str,
        omega2: float | None,
        alpha2: float | None,
    ) -> tuple[
        _F64,
        _F64,
        npt.NDArray[np.int8],
        npt.NDArray[np.uint32],
        _F64,
        tuple[_F64, _F64] | None,
        tuple[_F64, _F64] | None,
    ]: ...
    def closed_form(self, theta2: _F64, mode: str) -> tuple[_F64, _F64, npt.NDArray[np.int8]]: ...
    def velocity(
        self, theta2: _F64, theta3: _F64, theta4: _F64, omega2: _F64
    ) -> tuple[_F64, _F64, npt.NDArray[np.int8]]: ...
    def acceleration(
        self, theta2: _F64, theta3: _F64, theta4: _F64, omega2: _F64, alpha2: _F64
    ) -> tuple[_F64, _F64, npt.NDArray[np.int8]]: ...
    def coupler_point(
        self, theta2: _F64, theta3: _F64, p: float, delta: float
    ) -> tuple[_F64, _F64]: ...
    def limits(
        self, mode: str
    ) -> tuple[
        list[float],
        list[float],
        list[tuple[float, float]],
        bool,
        tuple[tuple[float, float], tuple[float, float]] | None,
    ]: ...
    def grashof(self) -> tuple[str, str, str, str, float, float, float, float]: ...

def transmission(theta3: _F64, theta4: _F64) -> tuple[_F64, _F64]: ...
def sweep_batch(
    links: npt.NDArray[np.float64],
    theta2: _F64,
    mode: str,
    tol: float,
    max_iter: int,
    predictor: str,
    method: str,
    threads: int | None,
) -> tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.int8],
    npt.NDArray[np.uint32],
    npt.NDArray[np.float64],
]: ...
def closed_form_batch(
    links: npt.NDArray[np.float64],
    theta2: _F64,
    mode: str,
    threads: int | None,
    out: tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]] | None = None,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...

_I8: TypeAlias = npt.NDArray[np.int8]
_Assemblies: TypeAlias = tuple[
    list[tuple[_F64, str, float, list[float]]], list[list[int]], list[list[int]], int, int
]
_Trace: TypeAlias = tuple[_F64, _F64, _F64, list[float], bool, list[float]]

@final
class Scene:
    @property
    def input_angle(self) -> float: ...
    @property
    def gruebler(self) -> int: ...
    @property
    def joint_count(self) -> int: ...
    @property
    def size(self) -> float: ...
    @property
    def max_step(self) -> float: ...
    def default_inputs(self, stroke: tuple[float, float] | None = None) -> _F64: ...
    def linear_output(self, points: list[int], coords: _F64) -> _F64 | None: ...
    def assemblies(self, theta: float, seed: int, runs: int) -> _Assemblies: ...
    def trace(self, start: _F64 | None, step: float, max_points: int) -> _Trace: ...
    def pose_gradient(self, points: _F64, free: list[tuple[int, int]], relative: bool) -> _F64: ...
    def dets_gradient(
        self,
        points: _F64,
        dpoints: _F64,
        free: list[tuple[int, int]],
        outputs: list[str] | None = None,
    ) -> _F64: ...
    def circuits(
        self, theta: float, seed: int, runs: int, step: float, max_points: int
    ) -> tuple[
        _Assemblies,
        list[tuple[list[int], list[float], float, tuple[float, float], _Trace]],
    ]: ...
    def plan(self, outputs: list[str] | None = None) -> Plan: ...

_Joint = tuple[str, str, tuple[str, str]]

_Loaded = tuple[
    Scene,
    tuple[str | None, str | None, str | None],
    dict[str, tuple[float, float]],
    dict[str, tuple[str, ...]],
    str,
    list[tuple[str, str]],
    list[tuple[str, str]] | None,
    list[str] | None,
    list[tuple[str, _Joint]],
    list[tuple[str, _Joint]],
    list[tuple[str, str, float]] | None,
    tuple[list[float] | None, dict[str, str] | None, dict[str, Any] | None, dict[str, Any] | None],
]

def load_scene(data: object) -> _Loaded: ...
def load_scene_json(text: str, stem: str) -> _Loaded | None: ...

@final
class Plan:
    @property
    def steps(self) -> list[tuple[str, list[int], list[int]]]: ...
    @property
    def points(self) -> list[int]: ...
    @property
    def links(self) -> list[int]: ...
    def stroke(
        self, size: float, tol: float, max_iter: int, max_step: float
    ) -> tuple[float, float]: ...
    def sweep(
        self,
        theta: _F64,
        tol: float,
        max_iter: int,
        max_step: float,
        omega: float | None,
        predictor: str,
    ) -> tuple[
        _F64, _F64, _I8, npt.NDArray[np.uint32], _F64, _F64, _I8, _F64, _I8,
        tuple[_F64, _F64, _F64, _F64] | None,
    ]: ...  # fmt: skip

def set_simd(enabled: bool) -> bool: ...
def simd_enabled() -> bool: ...
def simd_available() -> bool: ...

ATLAS_DESCRIPTOR: int
ATLAS_HARMONICS: int
ATLAS_SAMPLES: int
ATLAS_TOPOLOGIES: list[tuple[str, int, int]]

def atlas_shard(
    topology_name: str, seed: int, start: int, count: int
) -> tuple[_F64, npt.NDArray[np.int8], npt.NDArray[np.bool_], _F64, npt.NDArray[np.float32]]: ...
def atlas_describe(points: _F64, closed: bool) -> npt.NDArray[np.float32] | None: ...
def atlas_curve(
    topology_name: str, params: _F64, signs: _F64, samples: int
) -> tuple[_F64, _F64, bool, float] | None: ...
def atlas_pose(
    topology_name: str, params: _F64, signs: _F64, theta: float
) -> tuple[list[str], _F64, float] | None: ...
def atlas_match(
    topology_name: str,
    params: _F64,
    signs: _F64,
    target: _F64,
    closed: bool,
    offsets: int,
    resolution: int,
) -> tuple[_F64, _F64, _F64, _F64, npt.NDArray[np.bool_], _F64]: ...
def atlas_match_curves(
    points: _F64,
    theta: _F64,
    closed: list[bool],
    target: _F64,
    target_closed: bool,
    offsets: int,
    resolution: int,
) -> tuple[_F64, _F64, _F64, _F64, npt.NDArray[np.bool_], _F64]: ...
