"""``lynxsim demo`` writes ``index.html``: it loads clean in Chromium and every link resolves."""

from __future__ import annotations

from pathlib import Path
from urllib.parse import unquote, urlparse

import pytest

from lynxsim.cli import main
from tests.helpers import short_arm_task, short_rrr_task


@pytest.fixture(scope="module")
def demo_out(tmp_path_factory) -> Path:
    """A demo of one short arm task and one short 3-RRR task (fast videos)."""
    root = tmp_path_factory.mktemp("demo")
    tasks = root / "tasks"
    tasks.mkdir()
    (tasks / "short.toml").write_text(short_arm_task())
    (tasks / "short_rrr.toml").write_text(short_rrr_task())
    out = root / "out"
    argv = ["demo", "--tasks", str(tasks), "--out-dir", str(out), "--quality", "fast"]
    assert main([*argv, "--quiet", "--jobs", "2"]) == 0
    return out


def _local(url: str) -> Path:
    parsed = urlparse(url)
    assert parsed.scheme == "file", url
    return Path(unquote(parsed.path))


@pytest.mark.slow
def test_index_loads_clean_and_every_link_and_image_resolves(browser, demo_out):
    index = demo_out / "index.html"
    page, log = browser.open(index.as_uri())
    hrefs = page.eval_on_selector_all("a[href]", "els => els.map(e => e.href)")
    images = page.eval_on_selector_all(
        "img", "els => els.map(e => [e.src, e.complete && e.naturalWidth > 0])"
    )
    targets = [_local(h) for h in hrefs] + [_local(src) for src, _ in images]
    assert targets
    missing = [str(p) for p in targets if not p.is_file()]
    assert not missing
    assert all(p.resolve().is_relative_to(demo_out.resolve()) for p in targets)
    for _, image in images:  # every image scrolled to and decoded
        assert image
    log.assert_clean()
    rows = page.locator("table.runs tbody tr")
    assert rows.count() == 8  # every arm type and the 3-RRR run
    for i in range(rows.count()):
        labels = rows.nth(i).locator("a").all_inner_texts()
        assert labels == ["replay", "video", "report"]
    suffixes = {p.suffix for p in targets}
    assert {".html", ".mp4", ".json", ".png", ".txt"} <= suffixes
    page.close()


@pytest.mark.slow
def test_every_replay_the_index_links_opens_clean(browser, demo_out):
    page, log = browser.open((demo_out / "index.html").as_uri())
    replays = page.eval_on_selector_all(
        "table.runs a", "els => els.filter(e => e.textContent === 'replay').map(e => e.href)"
    )
    page.close()
    assert len(replays) == 8
    for url in replays:
        replay, replay_log = browser.open(url)
        state = replay.evaluate("window.lynxsimReplay.state()")
        assert state["draws"] >= 1
        assert replay.evaluate("window.lynxsimReplay.frames") > 50
        replay_log.assert_clean()
        replay.close()
    log.assert_clean()
