"""How a solve ends: the Status codes (the kernel's, as an IntEnum) with their messages,
and the conditioning threshold below which a four-bar position is SINGULAR."""

from __future__ import annotations

from enum import IntEnum

#: A position whose conditioning |sin(theta4 - theta3)| min(r3, r4) / L is below this is
#: SINGULAR: rounding moves the angles by about c eps / conditioning (c measured up to
#: 1.75 near toggles), so above it every converged angle is within 1e-9 rad.
SINGULAR_THRESHOLD = 1e-6


class Status(IntEnum):
    """How one solve ended. Arrays of results carry these codes as ``int8``."""

    #: Residual and next Newton correction below ``tol``, on the requested assembly mode.
    CONVERGED = 0
    #: ``max_iter`` Newton steps were taken without reaching ``tol``.
    MAX_ITERATIONS = -2
    #: The input value, a residual or an iterate was NaN or infinite.
    NON_FINITE = -3
    #: Conditioning |sin(theta4 - theta3)| min(r3, r4) / L below the singular threshold:
    #: a dead (toggle) or change point, where the two assembly modes meet.
    SINGULAR = -4
    #: The loop cannot close at this input value (crank angle or displacement), known
    #: before any iteration.
    NOT_ASSEMBLABLE = -5
    #: Newton converged, but on the other assembly mode than the one requested.
    BRANCH_JUMP = -6
    #: The residual is below ``tol`` but rounding keeps the Newton correction above it:
    #: ``tol`` asks for more than double precision resolves at this point.
    PRECISION_LOSS = -7
    #: The input angle lies past a dead point of a group on the circuit being followed:
    #: the motion must reverse there (scene sweeps report the dead point's input angle).
    LIMIT = -8

    @property
    def message(self) -> str:
        """A one-line description."""
        return _MESSAGES[self]


_MESSAGES = {
    Status.CONVERGED: (
        "converged: residual and Newton correction below tolerance on the requested mode"
    ),
    Status.MAX_ITERATIONS: "maximum number of iterations reached without convergence",
    Status.NON_FINITE: "a non-finite value (NaN or infinity) was met",
    Status.SINGULAR: "singular: dead (toggle) or change point, the two modes meet",
    Status.NOT_ASSEMBLABLE: "not assemblable: the loop cannot close at this input value",
    Status.BRANCH_JUMP: "converged on the other assembly mode than the one requested",
    Status.PRECISION_LOSS: "tolerance below what double precision resolves at this point",
    Status.LIMIT: "past a dead point of the circuit followed: the input must reverse there",
}
