"""Workspaces of the 3-RRR robot: constant-orientation maps, orientation ranges.

* :func:`workspace_map` evaluates a grid of platform centres at one
  orientation: which legs reach, the leg-singularity measure and, for every
  working mode, the signed parallel-singularity measure (whose zero contour is
  the mode's parallel-singularity locus, :func:`parallel_singularity_loci`).
  The reachable set is the intersection of the three **leg annuli**
  (:func:`leg_annuli`), whose circles are the leg-singularity loci.

Orientation ranges at a point are in :mod:`lynxsim.rrr.orientation`.

The report calls such maps workspaces without qualification; they are
reachable constant-orientation workspaces. Link collisions are not modelled
here (the links may lie in different planes).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.angles import wrap_angle
from lynxsim.bounds import MAX_ANGLE_RAD, MAX_CELLS, MAX_COORDINATE_M, check_range
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import real_array, real_number
from lynxsim.rrr.geometry import RRR_ROBOT, RRRGeometry, check_rrr_geometry, rotation
from lynxsim.rrr.ik import REACH_TOL
from lynxsim.rrr.modes import MODE_SIGNS, N_MODES, _check_index

__all__ = [
    "LegAnnuli",
    "WorkspaceMap",
    "grid_extent",
    "leg_annuli",
    "parallel_singularity_loci",
    "workspace_map",
    "workspace_maps",
]

FloatArray = npt.NDArray[np.float64]

_CHUNK_POINTS = 65_536

MAX_ORIENTATIONS = 10_000
"""Most orientations of one :func:`grid_extent` or :func:`workspace_maps` call."""


def _angle(value: object, name: str) -> float:
    """One finite angle within two turns [rad], or InvalidInputError / NonFiniteInputError."""
    v = real_number(value, name)
    if not math.isfinite(v):
        raise NonFiniteInputError(f"{name} must be finite, got {v!r} rad")
    return check_range(v, name, -MAX_ANGLE_RAD, MAX_ANGLE_RAD, "rad")


def _angles(values: object, name: str) -> list[float]:
    """A non-empty 1-D sequence of finite angles [rad], at most MAX_ORIENTATIONS."""
    arr = real_array(values, name)
    if arr.ndim != 1 or not 1 <= arr.size <= MAX_ORIENTATIONS:
        raise InvalidInputError(
            f"{name} must be 1 to {MAX_ORIENTATIONS:,} orientations [rad] in a 1-D sequence, "
            f"got shape {arr.shape}"
        )
    if not np.isfinite(arr).all():
        raise NonFiniteInputError(f"{name} must be finite, got {arr.tolist()!r}")
    return [_angle(v, f"{name}[{i}]") for i, v in enumerate(arr.tolist())]


def _one_mode(mode: object) -> int:
    """One working-mode index 0..7, or InvalidInputError."""
    index = _check_index(mode)  # type: ignore[arg-type]
    if index.ndim != 0:
        raise InvalidInputError(f"mode must be one integer in 0..7, got shape {index.shape}")
    return int(index)


class LegAnnuli(NamedTuple):
    """Where each leg reaches at one orientation: ``r_min <= |C - centre_i| <= r_max``.

    Attributes:
        centres: Annulus centres ``B_i - R(alpha) c_i``, shape (3, 2) [m].
        r_min: Inner radius ``|s_a - L|`` [m] (leg folded on this circle).
        r_max: Outer radius ``s_a + L`` [m] (leg stretched on this circle).
    """

    centres: FloatArray
    r_min: float
    r_max: float


def leg_annuli(alpha: float, geometry: RRRGeometry = RRR_ROBOT) -> LegAnnuli:
    """The three leg annuli of the platform centre at orientation ``alpha`` [rad].

    Raises:
        InvalidInputError: ``alpha`` is not one number, or a bad ``geometry``.
        NonFiniteInputError: ``alpha`` is NaN or infinite.
    """
    geometry = check_rrr_geometry(geometry)
    rot = rotation(_angle(alpha, "alpha"))
    return LegAnnuli(
        centres=geometry.base - geometry.platform @ rot.T,
        r_min=geometry.reach_min,
        r_max=geometry.reach_max,
    )


def grid_extent(
    alphas: Sequence[float], geometry: RRRGeometry = RRR_ROBOT, margin: float = 0.01
) -> tuple[float, float, float, float]:
    """A rectangle holding the constant-orientation workspaces of ``alphas``.

    Args:
        alphas: Orientations [rad].
        geometry: The robot description.
        margin: Added on every side [m].

    Returns:
        ``(x_min, x_max, y_min, y_max)`` [m].

    Raises:
        InvalidInputError: ``alphas`` is not 1 to :data:`MAX_ORIENTATIONS`
            numbers, ``margin`` not in [0, :data:`~lynxsim.bounds.MAX_COORDINATE_M`]
            m, or a bad ``geometry``.
        NonFiniteInputError: An orientation is NaN or infinite.
    """
    geometry = check_rrr_geometry(geometry)
    alphas = _angles(alphas, "alphas")
    margin = check_range(real_number(margin, "margin"), "margin", 0.0, MAX_COORDINATE_M, "m")
    boxes = []
    for a in alphas:
        ann = leg_annuli(a, geometry)
        lo = (ann.centres - ann.r_max).max(axis=0)
        hi = (ann.centres + ann.r_max).min(axis=0)
        boxes.append((lo, hi))
    lo = np.min([b[0] for b in boxes], axis=0) - margin
    hi = np.max([b[1] for b in boxes], axis=0) + margin
    return float(lo[0]), float(hi[0]), float(lo[1]), float(hi[1])


@dataclass(frozen=True)
class WorkspaceMap:
    """A constant-orientation workspace on a grid of platform centres.

    Arrays are indexed ``[iy, ix]`` (rows = y), ready for ``imshow``/``contour``.

    Attributes:
        x: Grid x coordinates, shape (nx,) [m].
        y: Grid y coordinates, shape (ny,) [m].
        alpha: Platform orientation [rad].
        leg_reachable: Whether leg ``i`` reaches, shape (ny, nx, 3).
        serial: Leg-singularity measure ``min_i |sin(elbow bend_i)|``, the
            same in every working mode, shape (ny, nx) [-]; NaN where unreachable.
        parallel: Signed parallel-singularity measure of every working mode
            (:class:`~lynxsim.rrr.jacobian.SingularityMeasures`), shape
            (ny, nx, 8) [-]; NaN where unreachable.
        theta: Actuated angles of every working mode, shape (ny, nx, 8, 3)
            [rad], NaN where unreachable; ``None`` unless asked for.
        geometry: The robot.
    """

    x: FloatArray
    y: FloatArray
    alpha: float
    leg_reachable: npt.NDArray[np.bool_]
    serial: FloatArray
    parallel: FloatArray
    theta: FloatArray | None = None
    geometry: RRRGeometry = field(default=RRR_ROBOT, repr=False, compare=False)

    @property
    def reachable(self) -> npt.NDArray[np.bool_]:
        """Centres every leg reaches (in all 8 working modes), shape (ny, nx)."""
        out: npt.NDArray[np.bool_] = np.asarray(self.leg_reachable.all(axis=-1))
        return out

    @property
    def cell_area(self) -> float:
        """Area of one grid cell [m²] (uniform grids)."""
        dx = abs(float(np.diff(self.x).mean())) if self.x.size > 1 else 0.0
        dy = abs(float(np.diff(self.y).mean())) if self.y.size > 1 else 0.0
        return dx * dy

    @property
    def area(self) -> float:
        """Reachable area estimated by counting cells [m²]."""
        return float(self.reachable.sum()) * self.cell_area

    def singularity_free(self, mode: int, margin: float = 0.05) -> npt.NDArray[np.bool_]:
        """Reachable centres whose mode-``mode`` measures both exceed ``margin``, (ny, nx).

        Raises:
            InvalidInputError: ``mode`` is not one integer in 0..7, or ``margin``
                not a number in [0, 10].
        """
        m = _one_mode(mode)
        margin = check_range(real_number(margin, "margin"), "margin", 0.0, 10.0)
        with np.errstate(invalid="ignore"):
            out: npt.NDArray[np.bool_] = (np.abs(self.parallel[..., m]) > margin) & (
                self.serial > margin
            )
        return out


def _grid_chunk(
    centres: FloatArray, alpha: float, geometry: RRRGeometry, with_theta: bool
) -> tuple[npt.NDArray[np.bool_], FloatArray, FloatArray, FloatArray | None]:
    """Reach masks, serial and parallel measures (and angles) of centres (k, 2).

    Only the centres every leg reaches are evaluated beyond the reach test.
    """
    s_a, ell, r_p = geometry.proximal, geometry.distal, geometry.platform_radius
    arms = geometry.platform @ rotation(alpha).T  # r_i = R c_i, (3, 2)
    k = len(centres)
    d_all = centres[:, None, :] + (arms - geometry.base)  # P_i - B_i, (k, 3, 2)
    rho_all = np.hypot(d_all[..., 0], d_all[..., 1])
    reach = (rho_all <= geometry.reach_max + REACH_TOL) & (
        rho_all >= geometry.reach_min - REACH_TOL
    )
    idx = np.flatnonzero(reach.all(axis=-1))
    parallel = np.full((k, N_MODES), np.nan)
    serial = np.full(k, np.nan)
    theta = np.full((k, N_MODES, 3), np.nan) if with_theta else None
    if idx.size == 0:
        return reach, serial, parallel, theta
    d, rho = d_all[idx], rho_all[idx]
    disc = (
        np.clip(s_a + ell - rho, 0.0, None)
        * np.clip(rho - s_a + ell, 0.0, None)
        * np.clip(rho + s_a - ell, 0.0, None)
        * (rho + s_a + ell)
    )
    root = np.sqrt(disc)  # = 2 s_a rho sin(gamma)
    # Proximal link a = s_a R(-sigma gamma) d / rho, written without angles:
    # s_a cos(gamma) / rho = (rho² + s_a² - L²) / (2 rho²), s_a sin(gamma) / rho = root / (2 rho²).
    inv = 1.0 / (2.0 * rho**2)
    kc = (rho**2 + s_a**2 - ell**2) * inv
    ks = root * inv
    dx, dy = d[..., 0], d[..., 1]
    # Normalised rows of A for each leg (axis 1) and elbow branch (first index).
    rows = []
    for sigma in (1.0, -1.0):
        nx = dx - (kc * dx + sigma * ks * dy)
        ny = dy - (kc * dy - sigma * ks * dx)
        rows.append((nx / ell, ny / ell, (arms[:, 0] * ny - arms[:, 1] * nx) / (ell * r_p)))
    sub = np.empty((idx.size, N_MODES))
    for b2 in (0, 1):
        for b3 in (0, 1):
            u0, u1, u2 = (c[:, 1] for c in rows[b2])
            v0, v1, v2 = (c[:, 2] for c in rows[b3])
            w0, w1, w2 = u1 * v2 - u2 * v1, u2 * v0 - u0 * v2, u0 * v1 - u1 * v0
            for b1 in (0, 1):
                r0, r1, r2 = (c[:, 0] for c in rows[b1])
                sub[:, b1 + 2 * b2 + 4 * b3] = r0 * w0 + r1 * w1 + r2 * w2
    parallel[idx] = sub
    serial[idx] = root.min(axis=-1) / (2.0 * s_a * ell)
    if theta is not None:
        phi = np.arctan2(dy, dx)
        gamma = np.arctan2(root, rho**2 + s_a**2 - ell**2)
        branches = wrap_angle(np.stack([phi - gamma, phi + gamma], axis=-1))  # (k', 3, 2)
        bits = (MODE_SIGNS < 0).astype(np.intp)
        theta[idx] = branches[:, np.broadcast_to(np.arange(3), (N_MODES, 3)), bits]
    return reach, serial, parallel, theta


def workspace_map(
    x: npt.ArrayLike,
    y: npt.ArrayLike,
    alpha: float,
    geometry: RRRGeometry = RRR_ROBOT,
    *,
    with_theta: bool = False,
) -> WorkspaceMap:
    """Evaluate the constant-orientation workspace on a grid, all 8 working modes.

    Args:
        x: Grid x coordinates of the platform centre, shape (nx,) [m].
        y: Grid y coordinates, shape (ny,) [m].
        alpha: Platform orientation [rad].
        geometry: The robot description.
        with_theta: Also return the actuated angles of every mode (8 × 3 floats
            per grid point).

    Returns:
        The :class:`WorkspaceMap`.

    Raises:
        InvalidInputError: ``x`` or ``y`` is not a non-empty 1-D array of finite
            real numbers within ±:data:`~lynxsim.bounds.MAX_COORDINATE_M`, the
            grid has more than :data:`~lynxsim.bounds.MAX_CELLS` points (checked
            before allocating), ``alpha`` is not a finite number within two
            turns (±720 deg), or a bad ``geometry``.
    """
    geometry = check_rrr_geometry(geometry)
    if not isinstance(with_theta, bool | np.bool_):
        raise InvalidInputError(f"with_theta must be True or False, got {with_theta!r}")
    xs = real_array(x, "x")
    ys = real_array(y, "y")
    for name, arr in (("x", xs), ("y", ys)):
        if arr.ndim != 1 or arr.size == 0 or not np.isfinite(arr).all():
            shown = np.array2string(arr, threshold=6)
            raise InvalidInputError(f"{name} must be a non-empty finite 1-D array, got {shown}")
        if np.abs(arr).max() > MAX_COORDINATE_M:
            raise InvalidInputError(
                f"{name} must lie within ±{MAX_COORDINATE_M:g} m, got up to {np.abs(arr).max():g} m"
            )
    if xs.size * ys.size > MAX_CELLS:
        raise InvalidInputError(
            f"a {xs.size:,} x {ys.size:,} grid has {xs.size * ys.size:,} points "
            f"(at most {MAX_CELLS:,})"
        )
    alpha = _angle(alpha, "alpha")
    gx, gy = np.meshgrid(xs, ys)
    centres = np.stack([gx.ravel(), gy.ravel()], axis=-1)
    n = len(centres)
    reach = np.empty((n, 3), dtype=bool)
    serial = np.empty(n)
    parallel = np.empty((n, N_MODES))
    theta = np.empty((n, N_MODES, 3)) if with_theta else None
    for start in range(0, n, _CHUNK_POINTS):
        stop = min(start + _CHUNK_POINTS, n)
        r, s, p, t = _grid_chunk(centres[start:stop], alpha, geometry, with_theta)
        reach[start:stop], serial[start:stop], parallel[start:stop] = r, s, p
        if theta is not None and t is not None:
            theta[start:stop] = t
    shape = (len(ys), len(xs))
    return WorkspaceMap(
        x=xs,
        y=ys,
        alpha=float(alpha),
        leg_reachable=reach.reshape(shape + (3,)),
        serial=serial.reshape(shape),
        parallel=parallel.reshape(shape + (N_MODES,)),
        theta=None if theta is None else theta.reshape(shape + (N_MODES, 3)),
        geometry=geometry,
    )


def parallel_singularity_loci(wmap: WorkspaceMap, mode: int) -> list[FloatArray]:
    """Polylines where working mode ``mode``'s parallel measure changes sign.

    Args:
        wmap: A :func:`workspace_map` result.
        mode: Working mode 0..7.

    Returns:
        Polylines of platform centres, each shape (k, 2) [m] (possibly empty list).

    Raises:
        InvalidInputError: ``wmap`` is not a :class:`WorkspaceMap`, or ``mode``
            not one integer in 0..7.
    """
    import contourpy  # matplotlib's contouring engine; imported only when needed

    if not isinstance(wmap, WorkspaceMap):
        raise InvalidInputError(f"wmap must be a WorkspaceMap, got {type(wmap).__name__}")
    m = _one_mode(mode)
    z = np.ma.masked_invalid(wmap.parallel[..., m])
    if z.count() == 0:
        return []
    gen = contourpy.contour_generator(wmap.x, wmap.y, z, line_type="Separate")
    lines = gen.lines(0.0)
    return [np.asarray(line, dtype=float) for line in lines]


MAX_GRID_POINTS = MAX_CELLS
"""Largest grid :func:`workspace_maps` accepts (points per orientation):
:data:`lynxsim.bounds.MAX_CELLS`."""


def workspace_maps(
    alphas: Sequence[float],
    extent: tuple[float, float, float, float],
    resolution: float,
    geometry: RRRGeometry = RRR_ROBOT,
) -> list[WorkspaceMap]:
    """Constant-orientation workspaces of several orientations on one grid.

    Args:
        alphas: Platform orientations [rad].
        extent: ``(x_min, x_max, y_min, y_max)`` of the grid [m] (e.g. from
            :func:`grid_extent`).
        resolution: Grid step [m] (> 0).
        geometry: The robot description.

    Returns:
        One :class:`WorkspaceMap` per orientation, in order.

    Raises:
        InvalidInputError: Not 1 to :data:`MAX_ORIENTATIONS` orientations, an
            ``extent`` that is not 4 finite numbers within
            ±:data:`~lynxsim.bounds.MAX_COORDINATE_M` with min <= max, a step
            that is not a positive number, a grid larger than
            :data:`MAX_GRID_POINTS` (checked before allocating; the message
            states the finest step the area allows), or a bad ``geometry``.
        NonFiniteInputError: An orientation or the step is NaN or infinite.
    """
    geometry = check_rrr_geometry(geometry)
    alphas = _angles(alphas, "alphas")
    box = real_array(extent, "extent")
    if box.shape != (4,):
        raise InvalidInputError(
            f"extent must be (x_min, x_max, y_min, y_max) [m], got shape {box.shape}"
        )
    x0, x1, y0, y1 = (
        check_range(v, f"extent[{i}]", -MAX_COORDINATE_M, MAX_COORDINATE_M, "m")
        for i, v in enumerate(box.tolist())
    )
    if x0 > x1 or y0 > y1:
        raise InvalidInputError(f"extent must have min <= max, got {box.tolist()} m")
    step = real_number(resolution, "resolution")
    if not math.isfinite(step):
        raise NonFiniteInputError(f"grid resolution must be finite, got {step!r} m")
    if not step > 0.0:
        raise InvalidInputError(f"grid resolution must be positive, got {step!r} m")
    # Point counts from the extent and step alone, before np.arange allocates them.
    fx, fy = (x1 - x0) / step + 1.5, (y1 - y0) / step + 1.5  # may be inf for a denormal step
    if fx * fy > MAX_GRID_POINTS:
        nx, ny = min(fx, 1e300), min(fy, 1e300)
        finest = math.sqrt(max((x1 - x0) * (y1 - y0), 1e-300) / MAX_GRID_POINTS)
        raise InvalidInputError(
            f"a {step * 1e3:g} mm grid over that area has about {nx * ny:.3g} points "
            f"(at most {MAX_GRID_POINTS:,}: a resolution of at least ~{finest * 1e3:.3g} mm)"
        )
    xs = np.arange(x0, x1 + step / 2, step)
    ys = np.arange(y0, y1 + step / 2, step)
    return [workspace_map(xs, ys, a, geometry) for a in alphas]
