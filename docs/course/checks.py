"""Checks of the course's exercises: call one with your answer; it passes or says what is wrong.

Each ``check_*`` function raises ``AssertionError`` with a hint when an answer is wrong and
prints a short confirmation when it is right. The reference values are the report's (its
tables and figures, as ``../shared/SPEC.md`` distils them, errata corrected) or properties
that any right answer has (a transform that is a rotation, an IK solution that FK maps back
onto the target); this module uses NumPy only, never lynxsim, so it checks lynxsim too.

Units as in the exercises: millimetres and degrees where the report uses them, SI elsewhere,
each named in the argument.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]

REPO = Path(__file__).resolve().parents[2]
"""The repository's root (the chapters read its task files, ``REPO / "tasks"``)."""

L2_MM = 153.0
"""Upper arm, shoulder to elbow [mm] (report's DH table, a_2)."""
L3_MM = 153.0
"""Forearm, elbow to wrist [mm] (a_3)."""


def _ok(what: str) -> None:
    print(f"correct: {what}")


def _close(name: str, got: Any, want: Any, tol: float, unit: str) -> None:
    got_a = np.asarray(got, dtype=float)
    want_a = np.asarray(want, dtype=float)
    assert got_a.shape == want_a.shape, f"{name}: expected shape {want_a.shape}, got {got_a.shape}"
    assert np.all(np.isfinite(got_a)), f"{name}: got non-finite values {got_a}"
    err = float(np.max(np.abs(got_a - want_a)))
    assert err <= tol, f"{name}: off by {err:.4g} {unit} (tolerance {tol} {unit}); got {got_a}"


# --- references (numpy only) -------------------------------------------------------------


def _rot_x(a: float) -> FloatArray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _rot_z(a: float) -> FloatArray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _trans(x: float, y: float, z: float) -> FloatArray:
    t = np.eye(4)
    t[:3, 3] = (x, y, z)
    return t


def _modified_dh(alpha: float, a: float, theta: float, d: float) -> FloatArray:
    """Craig's T = RotX(alpha) TransX(a) RotZ(theta) TransZ(d)."""
    return _rot_x(alpha) @ _trans(a, 0, 0) @ _rot_z(theta) @ _trans(0, 0, d)


# --- chapter 1: DH frames and forward kinematics ------------------------------------------


def check_dh_transform(dh: Callable[[float, float, float, float], Any]) -> None:
    """Your ``dh(alpha, a, theta, d)`` [rad, any length unit] is the modified DH transform.

    It must return the 4x4 homogeneous transform RotX(alpha) TransX(a) RotZ(theta) TransZ(d)
    (Craig's convention, the report's).
    """
    rng = np.random.default_rng(1)
    for _ in range(50):
        alpha, theta = rng.uniform(-np.pi, np.pi, 2)
        a, d = rng.uniform(-0.3, 0.3, 2)
        got = np.asarray(dh(alpha, a, theta, d), dtype=float)
        want = _modified_dh(alpha, a, theta, d)
        assert got.shape == (4, 4), f"expected a 4x4 matrix, got shape {got.shape}"
        err = float(np.max(np.abs(got - want)))
        assert err < 1e-9, (
            f"dh({alpha:.3f}, {a:.3f}, {theta:.3f}, {d:.3f}) is off by {err:.3g}; "
            "the modified convention rotates about x and translates along x first, "
            "then rotates about z and translates along z"
        )
    _ok("the modified DH transform")


def check_fk_figure7(tool_mm: Any) -> None:
    """The tool point [mm] of the report's second FK case (its Figure 7).

    Joints (deg): -6.61, 38.19, -144.24, 58.24, 63.00; the report prints
    (142.83, -16.56, -62.05) mm from inputs rounded to 0.01 deg (agreement to ~0.05 mm).
    """
    _close("tool point", tool_mm, [142.83, -16.56, -62.05], 0.05, "mm")
    _ok("the tool point of the report's Figure 7")


def check_pitch_figure4(pitch_deg: float) -> None:
    """The tool pitch [deg] of the report's first FK case (its Figure 4): q2 + q3 + q4."""
    _close("pitch", pitch_deg, 100.5 - 41.19 - 13.62, 1e-6, "deg")
    _ok("the tool pitch of the report's Figure 4")


# --- chapter 2: inverse kinematics, branches, workspace -----------------------------------


def check_ik_p2(q_deg: Any) -> None:
    """Joints q1..q4 [deg] that put the tool at the report's P2 (0, 250, 300) mm, pitch 0.

    The report's Table 4 (and its errata): (90, 80.38, -46.11, -34.27).
    """
    _close("q1..q4", np.asarray(q_deg, dtype=float)[:4], [90, 80.38, -46.11, -34.27], 0.01, "deg")
    _ok("the joints of P2")


def check_elbow_p1(elbow_mm: Any) -> None:
    """The elbow's (joint 3's origin) position [mm] at P1; the report: (0, 147.16, 104.89)."""
    _close("elbow", elbow_mm, [0.0, 147.16, 104.89], 0.01, "mm")
    _ok("the elbow at P1")


def check_wrist_reach(reach_mm: float) -> None:
    """The largest distance [mm] from the shoulder (joint 2) to the wrist (joint 4)."""
    _close("reach", reach_mm, L2_MM + L3_MM, 1e-6, "mm")
    _ok("the wrist's reach from the shoulder")


def check_two_link_ik(solve: Callable[[float, float], Any]) -> None:
    """Your ``solve(r, z)`` [mm] returns both elbow branches ``[(q2, q3), (q2, q3)]`` [rad].

    (r, z) is the wrist point in the arm's vertical plane, relative to the shoulder; the
    upper arm and the forearm are 153 mm each, q2 is measured from the horizontal and q3
    relative to the upper arm: r = l2 cos q2 + l3 cos(q2 + q3), z = l2 sin q2 + l3 sin(q2 + q3).
    The two branches have q3 of opposite signs.
    """
    rng = np.random.default_rng(2)
    for _ in range(50):
        dist = rng.uniform(20.0, 300.0)
        ang = rng.uniform(-np.pi / 2, np.pi / 2)
        r, z = dist * np.cos(ang), dist * np.sin(ang)
        got = np.asarray(solve(r, z), dtype=float)
        assert got.shape == (2, 2), f"solve({r:.1f}, {z:.1f}): expected 2 branches of (q2, q3)"
        for q2, q3 in got:
            rr = L2_MM * np.cos(q2) + L3_MM * np.cos(q2 + q3)
            zz = L2_MM * np.sin(q2) + L3_MM * np.sin(q2 + q3)
            err = float(np.hypot(rr - r, zz - z))
            assert err < 1e-6, (
                f"solve({r:.1f}, {z:.1f}) gave q2={q2:.4f}, q3={q3:.4f}, whose wrist lies "
                f"{err:.3g} mm from the target"
            )
        assert got[0, 1] * got[1, 1] < 0, (
            f"solve({r:.1f}, {z:.1f}): the two branches must be elbow-up and elbow-down "
            f"(q3 of opposite signs), got q3 = {got[:, 1]}"
        )
    _ok("both branches of the two-link IK")


# --- chapter 3: trajectories ---------------------------------------------------------------

CONTINUITY = {
    "free": "position",
    "cubic": "velocity",
    "quintic": "acceleration",
    "lspb": "velocity",
    "line": "acceleration",
    "ruckig": "acceleration",
}
"""The highest derivative each type keeps continuous through its waypoints."""


def check_quintic_coefficients(coefficients: Callable[[float, float, float], Any]) -> None:
    """Your ``coefficients(q0, qf, T)`` returns a0..a5 of q(t) = sum a_k t^k.

    Boundary conditions: q(0) = q0, q(T) = qf, zero velocity and acceleration at both ends.
    """
    rng = np.random.default_rng(3)
    for _ in range(30):
        q0, qf = rng.uniform(-2, 2, 2)
        duration = rng.uniform(0.2, 3.0)
        a = np.asarray(coefficients(q0, qf, duration), dtype=float)
        assert a.shape == (6,), f"expected 6 coefficients a0..a5, got shape {a.shape}"
        p = np.polynomial.Polynomial(a)
        v, acc = p.deriv(1), p.deriv(2)
        got = [p(0), p(duration), v(0), v(duration), acc(0), acc(duration)]
        want = [q0, qf, 0, 0, 0, 0]
        names = ["q(0)", "q(T)", "q'(0)", "q'(T)", "q''(0)", "q''(T)"]
        for n, g, w in zip(names, got, want, strict=True):
            assert abs(g - w) < 1e-8 * max(1.0, duration**3), (
                f"q0={q0:.3f}, qf={qf:.3f}, T={duration:.3f}: {n} = {g:.6g}, should be {w:.6g}"
            )
    _ok("the quintic's coefficients")


def check_continuity(answer: Mapping[str, str]) -> None:
    """For each type, the highest derivative that stays continuous through the waypoints.

    ``answer`` maps each of free, cubic, quintic, lspb, line, ruckig to one of
    "position", "velocity", "acceleration".
    """
    missing = sorted(set(CONTINUITY) - set(answer))
    assert not missing, f"no answer for {missing}"
    wrong = sorted(k for k in CONTINUITY if answer[k] != CONTINUITY[k])
    assert not wrong, f"look again at {wrong}: plot their velocity and acceleration"
    _ok("the continuity of every trajectory type")


def check_point_segment_distance(distance: Callable[[Any, Any, Any], Any]) -> None:
    """Your ``distance(p, a, b)``: distance from points p (N, 3) to the segment a-b, shape (N,)."""
    rng = np.random.default_rng(4)
    for _ in range(30):
        a, b = rng.uniform(-1, 1, (2, 3))
        p = rng.uniform(-2, 2, (20, 3))
        ab = b - a
        t = np.clip((p - a) @ ab / (ab @ ab), 0.0, 1.0)
        want = np.linalg.norm(p - (a + t[:, None] * ab), axis=1)
        got = np.asarray(distance(p, a, b), dtype=float)
        assert got.shape == want.shape, f"expected shape {want.shape}, got {got.shape}"
        err = float(np.max(np.abs(got - want)))
        assert err < 1e-9, (
            f"off by up to {err:.3g}; beyond the ends the nearest point is the end itself"
        )
    _ok("the distance to a segment")


# --- chapter 4: obstacles, via points, planning -------------------------------------------

CYLINDER_MM = (150.0, 150.0, 40.0, 0.0, 400.0)
"""The report's cylinder: axis (x, y), radius, bottom z and top z [mm]."""


def check_cylinder_distance(distance: Callable[[Any], Any]) -> None:
    """Your ``distance(p_mm)``: distance [mm] from points (N, 3) to the report's cylinder.

    The solid vertical cylinder of radius 40 mm about (150, 150) from z = 0 to 400 mm;
    negative inside (minus the depth to the nearest face), zero on its surface.
    """
    rng = np.random.default_rng(5)
    cx, cy, radius, z0, z1 = CYLINDER_MM
    p = rng.uniform([0, 0, -150], [300, 300, 550], (400, 3))
    radial = np.hypot(p[:, 0] - cx, p[:, 1] - cy) - radius
    axial = np.maximum(z0 - p[:, 2], p[:, 2] - z1)
    outside = np.hypot(np.maximum(radial, 0), np.maximum(axial, 0))
    want = np.where((radial <= 0) & (axial <= 0), np.maximum(radial, axial), outside)
    got = np.asarray(distance(p), dtype=float)
    assert got.shape == want.shape, f"expected shape {want.shape}, got {got.shape}"
    bad = np.abs(got - want) > 1e-6
    assert not bad.any(), (
        f"{int(bad.sum())} of {len(p)} points wrong, e.g. {p[bad][0].round(1)}: got "
        f"{got[bad][0]:.3f}, want {want[bad][0]:.3f} mm (above or below the cylinder the "
        "nearest point is on a flat face or its rim)"
    )
    _ok("the distance to the report's cylinder")


def check_via_point_verdicts(collides: Mapping[str, bool]) -> None:
    """Which types collide with the cylinder on the report's via-point task.

    ``collides`` maps "line" and "quintic" to True (hits the cylinder) or False.
    """
    want = {"line": False, "quintic": True}
    for kind, verdict in want.items():
        assert kind in collides, f"no verdict for {kind!r}"
        assert collides[kind] is verdict, (
            f"{kind}: look at the clearance of its samples again (the via points fix a "
            "path in Cartesian space; what does joint-space interpolation do between them?)"
        )
    _ok("the via points work for straight lines only")


def check_potential_field_failure(answer: str) -> None:
    """Why did the potential field stop? One letter.

    a: the goal is out of reach; b: it reached a local minimum where attraction and
    repulsion cancel; c: the obstacle moved; d: the joint limits are violated.
    """
    assert answer.strip().lower() == "b", "not that: what does its gradient do where it stops?"
    _ok("a local minimum")


# --- chapter 5: the 3-RRR ------------------------------------------------------------------

RRR_SA_MM = 170.0
"""Proximal link [mm]."""
RRR_L_MM = 130.0
"""Distal link [mm]."""
RRR_BASE_MM = np.array([[0.0, 0.0], [502.29, 0.0], [251.15, 435.0]])
"""Base joints B1..B3 [mm] (report)."""
RRR_PLATFORM_RADIUS_MM = 130.0
"""Platform joints' circle [mm]."""
RRR_DIRECTIONS_DEG = np.array([210.0, 330.0, 90.0])
"""Direction of each platform joint from the platform centre at alpha = 0 [deg]."""


def _platform_joints_mm(x: float, y: float, alpha_deg: float) -> FloatArray:
    ang = np.radians(RRR_DIRECTIONS_DEG + alpha_deg)
    return np.stack(
        [x + RRR_PLATFORM_RADIUS_MM * np.cos(ang), y + RRR_PLATFORM_RADIUS_MM * np.sin(ang)], axis=1
    )


def check_leg_ik(solve: Callable[[Any, Any], Any]) -> None:
    """Your ``solve(b_mm, p_mm)`` returns both proximal angles [rad] of one leg, shape (2,).

    b is the base joint, p the platform joint (2,) [mm]; the proximal link (170 mm) starts
    at b at angle theta, the distal link (130 mm) joins its end to p.
    """
    rng = np.random.default_rng(6)
    for _ in range(50):
        b = rng.uniform(-100, 100, 2)
        dist = rng.uniform(45.0, 295.0)
        ang = rng.uniform(-np.pi, np.pi)
        p = b + dist * np.array([np.cos(ang), np.sin(ang)])
        got = np.asarray(solve(b, p), dtype=float)
        assert got.shape == (2,), f"expected the two angles of the two branches, got {got.shape}"
        elbows = b + RRR_SA_MM * np.stack([np.cos(got), np.sin(got)], axis=1)
        err = np.abs(np.linalg.norm(elbows - p, axis=1) - RRR_L_MM)
        assert err.max() < 1e-6, (
            f"b={b.round(1)}, p={p.round(1)}: the distal link would be "
            f"{np.linalg.norm(elbows - p, axis=1).round(3)} mm long, not 130 mm"
        )
        gap = abs(np.angle(np.exp(1j * (got[0] - got[1]))))
        assert gap > 1e-6 or abs(dist - (RRR_SA_MM + RRR_L_MM)) < 1e-3, (
            "the two branches are the same angle: one elbow each side of the line b-p"
        )
    _ok("the leg's two branches")


def check_unreachable_leg(leg: int, distance_mm: float) -> None:
    """The report's pose (300, 250, -40 deg): which leg (1-3) cannot reach, and |P_i - B_i| [mm]."""
    d = np.linalg.norm(_platform_joints_mm(300.0, 250.0, -40.0) - RRR_BASE_MM, axis=1)
    far = int(np.argmax(d))
    assert leg == far + 1, f"leg {leg} reaches: compare every |P_i - B_i| with 170 + 130 mm"
    _close(f"|P{leg} - B{leg}|", distance_mm, d[far], 0.01, "mm")
    _ok(f"leg {leg} would need {d[far]:.2f} mm > 300 mm")


def check_working_modes(count: int) -> None:
    """How many working modes (IK branch choices) has the 3-RRR?"""
    assert count == 2**3, "each leg has two branches; how many combinations are there?"
    _ok("8 working modes")


# --- chapter 6: a first learning agent -----------------------------------------------------


def check_sparse_reward(reward: Callable[[Any, Any], Any]) -> None:
    """Your ``reward(achieved, desired)`` [m], shapes (N, 3): -1 farther than 25 mm, else 0."""
    rng = np.random.default_rng(7)
    desired = rng.uniform(-0.3, 0.3, (200, 3))
    offset = rng.standard_normal((200, 3))
    offset /= np.linalg.norm(offset, axis=1, keepdims=True)
    dist = rng.uniform(0.0, 0.05, 200)
    dist[:5] = [0.0, 0.0249, 0.0251, 0.05, 0.0]
    achieved = desired + dist[:, None] * offset
    want = -(dist > 0.025).astype(float)
    got = np.asarray(reward(achieved, desired), dtype=float)
    assert got.shape == want.shape, f"vectorise it: expected shape {want.shape}, got {got.shape}"
    bad = got != want
    assert not bad.any(), f"{int(bad.sum())} rewards wrong, e.g. at distance {dist[bad][0]:.4f} m"
    _ok("the sparse goal reward")


def check_agent(success_rate: float, episodes: int) -> None:
    """Your trained agent's success rate on held-out episodes: at least 0.8 over 20 or more."""
    assert episodes >= 20, f"evaluate on at least 20 held-out episodes, not {episodes}"
    assert 0.0 <= success_rate <= 1.0, f"a rate lies in 0..1, got {success_rate}"
    assert success_rate >= 0.8, f"{success_rate:.2f} < 0.8: train longer or tune the step size"
    _ok(f"the agent succeeds in {success_rate:.0%} of {episodes} held-out episodes")
