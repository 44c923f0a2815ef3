"""Numbers the report prints, in its units (mm, degrees), with SPEC's errata applied.

Used by ``lynxsim demo`` to show the reproduction and by the tests to check it.
"""

from __future__ import annotations

from typing import NamedTuple

__all__ = [
    "FK_CASES",
    "TABLE4",
    "TABLE4_P1_ELBOW_MM",
    "TABLE4_P1_WRIST_MM",
    "FKCase",
    "Table4Row",
]


class FKCase(NamedTuple):
    """A forward-kinematics case of the report's Figures 4 and 7."""

    q_deg: tuple[float, float, float, float, float]
    position_mm: tuple[float, float, float]
    pitch_deg: float


class Table4Row(NamedTuple):
    """A pick-and-place pose of the report's Table 4 and its joints.

    ``q_deg`` holds q1..q4; the report's printed joint-4 theta includes the
    -90 deg DH offset and its P1 joint 2 misprints 5.89 for 15.89 (SPEC 3.2).
    """

    name: str
    position_mm: tuple[float, float, float]
    pitch_deg: float
    q_deg: tuple[float, float, float, float]


FK_CASES = (
    FKCase((-25.27, 100.5, -41.19, -13.62, 154.6), (107.31, -50.66, 415.13), 45.69),
    FKCase((-6.61, 38.19, -144.24, 58.24, 63.00), (142.83, -16.56, -62.05), -47.80),
)

TABLE4 = (
    Table4Row("P1", (0.0, 300.0, 0.0), -90.0, (90.0, 15.89, -18.47, -87.42)),
    Table4Row("P2", (0.0, 250.0, 300.0), 0.0, (90.0, 80.38, -46.11, -34.27)),
    Table4Row("P3", (250.0, 0.0, 300.0), 0.0, (0.0, 80.38, -46.11, -34.27)),
    Table4Row("P4", (0.0, -250.0, 300.0), 0.0, (-90.0, 80.38, -46.11, -34.27)),
    Table4Row("P5", (0.0, -300.0, 0.0), -90.0, (-90.0, 15.89, -18.47, -87.42)),
)

TABLE4_P1_ELBOW_MM = (0.0, 147.16, 104.89)
TABLE4_P1_WRIST_MM = (0.0, 300.0, 98.0)
