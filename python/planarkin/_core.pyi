"""Type stubs of the extension module (checked with mypy.stubtest in CI)."""

from typing import TypeAlias, final

import numpy as np
import numpy.typing as npt

__version__: str
BUILD_PROFILE: str
SINGULAR_THRESHOLD: float
STATUSES: list[tuple[int, str, str]]
__all__ = [
    "BUILD_PROFILE",
    "FourBar",
    "SINGULAR_THRESHOLD",
    "STATUSES",
    "__version__",
    "closed_form_batch",
    "set_simd",
    "simd_available",
    "simd_enabled",
    "sweep_batch",
    "transmission",
]

_F64: TypeAlias = npt.NDArray[np.float64]

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
    links: npt.NDArray[np.float64], theta2: _F64, mode: str, threads: int | None
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
def set_simd(enabled: bool) -> bool: ...
def simd_enabled() -> bool: ...
def simd_available() -> bool: ...
