"""One Verdict: the codes the judge stores, the names the table, maps and summaries write."""

from __future__ import annotations

from lynxsim.plots.sweep_map import VERDICT_COLOURS
from lynxsim.sweep.table import VERDICTS
from lynxsim.verdicts import Verdict


def test_codes_and_names_are_the_sweeps():
    assert [int(v) for v in Verdict] == [0, 1, 2, 3, 4]
    assert Verdict.labels() == ("clear", "collided", "start_overlap", "invalid", "no_motion")
    assert Verdict.labels() == VERDICTS
    assert Verdict(2).label == "start_overlap"


def test_the_maps_colour_every_verdict_but_clear():
    assert set(VERDICT_COLOURS) == set(Verdict.labels()) - {Verdict.CLEAR.label}
