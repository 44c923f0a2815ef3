"""Working modes of the 3-RRR robot: which way each leg's elbow is bent.

Each leg reaches its platform joint with two elbow branches. The branch of leg
``i`` is its **elbow sign**

    ``sigma_i = sign(z · ((E_i - B_i) × (P_i - E_i)))``,

+1 when the distal link turns counter-clockwise from the proximal link (the
elbow lies to the right of the line from ``B_i`` to ``P_i``), -1 when it turns
clockwise. The three signs make one of 8 **working modes**, numbered 0..7:
bit ``i`` of the mode index is set when leg ``i + 1`` has sigma = -1.

=====  =============  =====  =============
index  signs          index  signs
=====  =============  =====  =============
0      (+1, +1, +1)   4      (+1, +1, -1)
1      (-1, +1, +1)   5      (-1, +1, -1)
2      (+1, -1, +1)   6      (+1, -1, -1)
3      (-1, -1, +1)   7      (-1, -1, -1)
=====  =============  =====  =============

With ``theta_i`` the proximal angle and ``phi_i`` the direction of
``P_i - B_i``, sigma = +1 means ``theta_i = phi_i - gamma_i`` with the
interior angle ``gamma_i`` in [0, pi] at ``B_i``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_SAMPLES
from lynxsim.errors import InvalidInputError, short
from lynxsim.run_options import RunOption

__all__ = [
    "HOME_MODE",
    "MODE_OPTION",
    "MODE_SIGNS",
    "N_MODES",
    "mode_index",
    "mode_label",
    "mode_signs",
]

N_MODES = 8
"""Number of working modes (two elbow branches for each of three legs)."""
HOME_MODE = 7
"""Working mode of the model's ``home`` pose and of runs by default: elbow signs - - -,
the mode the university report draws (its ``arm.m`` takes the ``+`` root of its
half-angle quadratic)."""

MODE_OPTION = RunOption(
    name="mode",
    help=f"working mode of the inverse kinematics (default {HOME_MODE}, the report's)",
    type=int,
    default=HOME_MODE,
    choices=tuple(range(N_MODES)),
    metavar=f"0..{N_MODES - 1}",
)
"""The option of a 3-RRR run (``lynxsim play --mode``): its working mode."""

MODE_SIGNS: npt.NDArray[np.int8] = np.array(
    [[-1 if (m >> leg) & 1 else 1 for leg in range(3)] for m in range(N_MODES)], dtype=np.int8
)
"""Elbow signs of every working mode, shape (8, 3), row = mode index (read-only)."""
MODE_SIGNS.setflags(write=False)


def _check_index(mode: npt.ArrayLike) -> npt.NDArray[np.intp]:
    """``mode`` as an intp array of indices in 0..7, or InvalidInputError."""
    try:
        m = np.asarray(mode)
    except (TypeError, ValueError, OverflowError):
        m = np.asarray(None)
    if (
        not np.issubdtype(m.dtype, np.integer)
        or m.size > _MAX_INDICES
        or ((m < 0) | (m >= N_MODES)).any()
    ):
        raise InvalidInputError(
            f"working mode must be an integer in 0..7 (or an integer array), got {short(mode)}"
        )
    return m.astype(np.intp)


_MAX_INDICES = MAX_SAMPLES
"""Most mode indices of one call."""


def mode_signs(mode: npt.ArrayLike) -> npt.NDArray[np.int8]:
    """Elbow signs of working mode(s).

    Args:
        mode: Mode index or indices in 0..7, any shape.

    Returns:
        Shape mode.shape + (3,), entries ±1.

    Raises:
        InvalidInputError: If an index is not an integer in 0..7.
    """
    return MODE_SIGNS[_check_index(mode)]


def mode_index(signs: npt.ArrayLike | Sequence[int]) -> npt.NDArray[np.intp]:
    """Working-mode index of elbow signs (the inverse of :func:`mode_signs`).

    Args:
        signs: Elbow signs, shape (..., 3), entries ±1.

    Returns:
        Mode indices, shape (...).

    Raises:
        InvalidInputError: If the last axis is not 3 or an entry is not ±1.
    """
    try:
        s = np.asarray(signs)
    except (TypeError, ValueError, OverflowError):
        s = np.asarray(None)
    if (
        s.dtype.kind not in "iuf"
        or s.ndim == 0
        or s.shape[-1] != 3
        or s.size > 3 * _MAX_INDICES
        or not np.isin(s, (-1, 1)).all()
    ):
        raise InvalidInputError(f"elbow signs must be ±1 with shape (..., 3), got {short(signs)}")
    bits = (s < 0).astype(np.intp)
    out: npt.NDArray[np.intp] = bits[..., 0] + 2 * bits[..., 1] + 4 * bits[..., 2]
    return out


def mode_label(mode: int) -> str:
    """Short text for a working mode, e.g. ``"+-+"`` for mode 2.

    Raises:
        InvalidInputError: If ``mode`` is not one integer in 0..7.
    """
    if np.ndim(_check_index(mode)) != 0:
        raise InvalidInputError(f"mode_label takes one working mode, got {short(mode)}")
    return "".join("+" if s > 0 else "-" for s in mode_signs(mode))
