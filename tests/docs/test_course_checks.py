"""The course's exercise checks (docs/course/checks.py) pass right answers and fail wrong ones.

Right answers here are written independently of the checks: the report's printed values
(SPEC §1-§2), or solutions coded from the textbook formulas; every wrong answer is a
mistake a student makes (a swapped product, a lost sign, a unit slip, an off-by-one).
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

CHECKS_PATH = Path(__file__).resolve().parents[2] / "docs" / "course" / "checks.py"


def _load_checks() -> ModuleType:
    spec = importlib.util.spec_from_file_location("course_checks", CHECKS_PATH)
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["course_checks"] = module
    spec.loader.exec_module(module)
    return module


checks = _load_checks()


def _rx(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _rz(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _tx(x: float) -> np.ndarray:
    t = np.eye(4)
    t[0, 3] = x
    return t


def _tz(z: float) -> np.ndarray:
    t = np.eye(4)
    t[2, 3] = z
    return t


def _dh_closed_form(alpha: float, a: float, theta: float, d: float) -> np.ndarray:
    """Craig's eq. 3.6, the matrix written out."""
    ca, sa, ct, st = np.cos(alpha), np.sin(alpha), np.cos(theta), np.sin(theta)
    return np.array(
        [
            [ct, -st, 0, a],
            [st * ca, ct * ca, -sa, -sa * d],
            [st * sa, ct * sa, ca, ca * d],
            [0, 0, 0, 1.0],
        ]
    )


def _two_link(
    r: float, z: float, l2: float = 153.0, l3: float = 153.0
) -> list[tuple[float, float]]:
    c3 = (r * r + z * z - l2 * l2 - l3 * l3) / (2 * l2 * l3)
    out = []
    for s3 in (np.sqrt(1 - c3 * c3), -np.sqrt(1 - c3 * c3)):
        q3 = np.arctan2(s3, c3)
        out.append((np.arctan2(z, r) - np.arctan2(l3 * s3, l2 + l3 * c3), q3))
    return out


def _quintic(q0: float, qf: float, t: float) -> np.ndarray:
    h = qf - q0
    return np.array([q0, 0.0, 0.0, 10 * h / t**3, -15 * h / t**4, 6 * h / t**5])


def _segment_distance(p: Any, a: Any, b: Any) -> np.ndarray:
    p, a, b = (np.asarray(v, dtype=float) for v in (p, a, b))
    ab = b - a
    t = np.clip((p - a) @ ab / (ab @ ab), 0.0, 1.0)
    return np.linalg.norm(p - a - t[:, None] * ab, axis=1)


def _cylinder_distance(p: Any, radius: float = 40.0, top: float = 400.0) -> np.ndarray:
    p = np.asarray(p, dtype=float)
    radial = np.hypot(p[:, 0] - 150.0, p[:, 1] - 150.0) - radius
    axial = np.maximum(-p[:, 2], p[:, 2] - top)
    outside = np.hypot(np.maximum(radial, 0.0), np.maximum(axial, 0.0))
    inside = np.maximum(radial, axial)
    return np.where((radial <= 0) & (axial <= 0), inside, outside)


def _leg(b: Any, p: Any, sa: float = 170.0, length: float = 130.0) -> np.ndarray:
    d = np.asarray(p, dtype=float) - np.asarray(b, dtype=float)
    phi = np.arctan2(d[1], d[0])
    half = np.arccos(np.clip((d @ d + sa * sa - length * length) / (2 * sa * np.hypot(*d)), -1, 1))
    return np.array([phi + half, phi - half])


def _sparse(achieved: Any, desired: Any, threshold: float = 0.025) -> np.ndarray:
    dist = np.linalg.norm(np.asarray(achieved) - np.asarray(desired), axis=-1)
    return np.where(dist > threshold, -1.0, 0.0)


RIGHT: list[tuple[str, Callable[[], None]]] = [
    ("dh", lambda: checks.check_dh_transform(_dh_closed_form)),
    ("fk_figure7", lambda: checks.check_fk_figure7([142.83, -16.56, -62.05])),
    ("pitch_figure4", lambda: checks.check_pitch_figure4(45.69)),
    ("ik_p2", lambda: checks.check_ik_p2([90.0, 80.38, -46.11, -34.27, 0.0])),
    ("elbow_p1", lambda: checks.check_elbow_p1([0.0, 147.16, 104.89])),
    ("wrist_reach", lambda: checks.check_wrist_reach(306.0)),
    ("two_link", lambda: checks.check_two_link_ik(_two_link)),
    ("quintic", lambda: checks.check_quintic_coefficients(_quintic)),
    (
        "continuity",
        lambda: checks.check_continuity(
            {
                "free": "position",
                "cubic": "velocity",
                "lspb": "velocity",
                "quintic": "acceleration",
                "line": "acceleration",
                "ruckig": "acceleration",
            }
        ),
    ),
    ("segment", lambda: checks.check_point_segment_distance(_segment_distance)),
    ("cylinder", lambda: checks.check_cylinder_distance(_cylinder_distance)),
    ("via_points", lambda: checks.check_via_point_verdicts({"line": False, "quintic": True})),
    ("potential", lambda: checks.check_potential_field_failure("b")),
    ("leg_ik", lambda: checks.check_leg_ik(_leg)),
    ("unreachable_leg", lambda: checks.check_unreachable_leg(1, 322.29)),
    ("modes", lambda: checks.check_working_modes(8)),
    ("sparse_reward", lambda: checks.check_sparse_reward(_sparse)),
    ("agent", lambda: checks.check_agent(0.85, 20)),
]

WRONG: list[tuple[str, Callable[[], None]]] = [
    # chapter 1: the standard (distal) convention instead of the modified one
    (
        "dh_standard",
        lambda: checks.check_dh_transform(lambda al, a, th, d: _rz(th) @ _tz(d) @ _tx(a) @ _rx(al)),
    ),
    (
        "dh_no_twist",
        lambda: checks.check_dh_transform(lambda al, a, th, d: _tx(a) @ _rz(th) @ _tz(d)),
    ),
    ("fk_figure7_metres", lambda: checks.check_fk_figure7([0.14283, -0.01656, -0.06205])),
    ("fk_figure7_sign", lambda: checks.check_fk_figure7([142.83, 16.56, -62.05])),
    ("fk_figure7_shape", lambda: checks.check_fk_figure7([142.83, -16.56])),
    ("pitch_figure4_offset", lambda: checks.check_pitch_figure4(45.69 - 90.0)),
    # chapter 2: Table 4's misprint, the DH offset left in q4, the other branch, a unit slip
    ("ik_p2_offset", lambda: checks.check_ik_p2([90.0, 80.38, -46.11, -124.27])),
    ("ik_p2_branch", lambda: checks.check_ik_p2([90.0, 34.27, 46.11, -80.38])),
    ("elbow_p1_wrist", lambda: checks.check_elbow_p1([0.0, 300.0, 98.0])),
    ("wrist_reach_tool", lambda: checks.check_wrist_reach(306.0 + 98.0)),
    (
        "two_link_one_branch",
        lambda: checks.check_two_link_ik(lambda r, z: [_two_link(r, z)[0]] * 2),
    ),
    (
        "two_link_lengths",
        lambda: checks.check_two_link_ik(lambda r, z: _two_link(r, z, 150.0, 150.0)),
    ),
    # chapter 3: the report's typo (a dropped factor), a missing entry, a wrong type
    (
        "quintic_typo",
        lambda: checks.check_quintic_coefficients(
            lambda q0, qf, t: _quintic(q0, qf, t) * [1, 1, 1, 1, 1, 0.5]
        ),
    ),
    (
        "quintic_cubic",
        lambda: checks.check_quintic_coefficients(
            lambda q0, qf, t: np.array([q0, 0, 3 * (qf - q0) / t**2, -2 * (qf - q0) / t**3, 0, 0])
        ),
    ),
    ("continuity_missing", lambda: checks.check_continuity({"free": "position"})),
    (
        "continuity_cubic",
        lambda: checks.check_continuity(
            {
                "free": "position",
                "cubic": "acceleration",
                "lspb": "velocity",
                "quintic": "acceleration",
                "line": "acceleration",
                "ruckig": "acceleration",
            }
        ),
    ),
    (
        "segment_infinite_line",
        lambda: checks.check_point_segment_distance(
            lambda p, a, b: _segment_distance(p, a - 100 * (b - a), b + 100 * (b - a))
        ),
    ),
    # chapter 4: the axis distance only, a 50 mm radius, no sign inside
    (
        "cylinder_axis",
        lambda: checks.check_cylinder_distance(
            lambda p: np.hypot(p[:, 0] - 150, p[:, 1] - 150) - 40
        ),
    ),
    (
        "cylinder_radius",
        lambda: checks.check_cylinder_distance(lambda p: _cylinder_distance(p, radius=50.0)),
    ),
    (
        "cylinder_unsigned",
        lambda: checks.check_cylinder_distance(lambda p: np.abs(_cylinder_distance(p))),
    ),
    (
        "via_points_swapped",
        lambda: checks.check_via_point_verdicts({"line": True, "quintic": False}),
    ),
    (
        "via_points_all_clear",
        lambda: checks.check_via_point_verdicts({"line": False, "quintic": False}),
    ),
    ("via_points_missing", lambda: checks.check_via_point_verdicts({"line": False})),
    ("potential_a", lambda: checks.check_potential_field_failure("a")),
    # chapter 5: one branch twice, link lengths swapped, the wrong leg, the report's frame error
    ("leg_ik_one_branch", lambda: checks.check_leg_ik(lambda b, p: np.repeat(_leg(b, p)[:1], 2))),
    ("leg_ik_swapped", lambda: checks.check_leg_ik(lambda b, p: _leg(b, p, 130.0, 170.0))),
    ("unreachable_leg_2", lambda: checks.check_unreachable_leg(2, 322.29)),
    ("unreachable_leg_distance", lambda: checks.check_unreachable_leg(1, 300.0)),
    ("modes_6", lambda: checks.check_working_modes(6)),
    # chapter 6: the sign flipped, >= at the threshold, a 2.5 mm threshold, too few episodes
    ("sparse_sign", lambda: checks.check_sparse_reward(lambda a, d: -_sparse(a, d))),
    ("sparse_threshold", lambda: checks.check_sparse_reward(lambda a, d: _sparse(a, d, 0.0025))),
    ("sparse_scalar", lambda: checks.check_sparse_reward(lambda a, d: _sparse(a, d).sum())),
    ("agent_weak", lambda: checks.check_agent(0.5, 20)),
    ("agent_few_episodes", lambda: checks.check_agent(1.0, 5)),
    ("agent_not_a_rate", lambda: checks.check_agent(17.0, 20)),
]


@pytest.mark.parametrize("answer", [a for _, a in RIGHT], ids=[n for n, _ in RIGHT])
def test_a_right_answer_passes(
    answer: Callable[[], None], capsys: pytest.CaptureFixture[str]
) -> None:
    answer()
    assert capsys.readouterr().out.startswith("correct: ")


@pytest.mark.parametrize("answer", [a for _, a in WRONG], ids=[n for n, _ in WRONG])
def test_a_wrong_answer_fails(answer: Callable[[], None]) -> None:
    with pytest.raises(AssertionError):
        answer()


def test_every_check_is_exercised_both_ways() -> None:
    names = {n for n in dir(checks) if n.startswith("check_")}
    right = {n for n in names if any(n in (f.__code__.co_names) for _, f in RIGHT)}
    wrong = {n for n in names if any(n in (f.__code__.co_names) for _, f in WRONG)}
    assert right == names, f"no right answer tried for {sorted(names - right)}"
    assert wrong == names, f"no wrong answer tried for {sorted(names - wrong)}"


def test_checks_import_no_lynxsim() -> None:
    """The checks judge lynxsim's answers too, so they must not be computed by it."""
    code = (
        "import importlib.util, sys; "
        f"spec = importlib.util.spec_from_file_location('c', {str(CHECKS_PATH)!r}); "
        "m = importlib.util.module_from_spec(spec); spec.loader.exec_module(m); "
        "print(sorted(n for n in sys.modules if n.split('.')[0] in ('lynxsim', 'mujoco')))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
