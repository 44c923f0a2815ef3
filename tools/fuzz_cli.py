"""Fuzz campaign over the command line, in-process: argument sets and the rules every run keeps.

    python tools/fuzz_cli.py --runs 2000 --seed 0

Prints the counts by exit code and every run that broke a rule (with its
arguments, to reproduce with ``lynxsim ARGS``); exits 1 if any did. The quick
hypothesis test ``tests/fuzz/test_fuzz_cli.py`` draws from the same generator.
A run keeps the rules when:

- no exception escapes :func:`lynxsim.cli.main` (argparse's ``SystemExit`` with
  code 0 or 2 is its documented way out);
- the exit code is 0, 1 or 2, and a non-zero exit prints exactly one line on stderr;
- nothing is written outside the sandbox folder the run starts in, and no file
  in it is a partial one (a temporary name of :func:`lynxsim.fileio.atomic_path`);
- ``Infinity``/``NaN`` never appear in the output of a successful run.
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import io
import os
import random
import sys
import tempfile
import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from lynxsim.cli import main as lynxsim_main
from tests.helpers import short_arm_task, short_rrr_task

__all__ = ["CliOutcome", "argument_sets", "check_run", "main", "make_sandbox", "random_argv"]

NUMBERS = [
    "0", "1", "-1", "90", "-90", "300", "-9e1", "-.5", "1e3", "1e12", "-1e12", "1e308",
    "1e309", "5e-324", "1e-300", "-0", "nan", "-nan", "inf", "-inf", "Infinity", "0x10",
    "1_000", "1" + "0" * 400, "", " ", "x", "1,5", "١٢", "--", "-", "1e", "e1",
]  # fmt: skip
"""Numeric positions: valid, negative literals, huge, tiny, non-finite, malformed."""

WORDS = [
    "arm", "rrr", "quintic", "ruckig", "planned", "front", "top", "side", "fast", "-h", "npz",
    "minari", "ray", "local", "1-3", "3-1", "LynxReach-v1", "a/b-v0",
]  # fmt: skip
"""Other tokens: names, choices, wrong choices."""

FLAGS: dict[str, list[str]] = {
    "fk": ["--si", "--json", "--frames"],
    "ik": ["--si", "--json", "--all"],
    "workspace": ["--samples", "--seed", "--out", "--quiet"],
    "traj": [
        "--type", "--out-dir", "--rate-hz", "--format", "--si", "--segment-duration-s",
        "--shortest", "--stretch", "--no-stretch", "--pass-through", "--no-compare", "--list",
    ],
    "play": [
        "--type", "--out", "--no-video", "--no-obstacle", "--camera", "--mode", "--quality",
        "--fps", "--json", "--quiet", "--html",
    ],
    "view": ["--out", "--quiet"],
    "plan": [
        "--planner", "--margin-mm", "--seed", "--time-limit-s", "--out-dir", "--format",
        "--rate-hz", "--si", "--json", "--quiet",
    ],
    "rrr fk": ["--si", "--json", "--mode"],
    "rrr ik": ["--si", "--json", "--mode"],
    "rrr workspace": ["--alpha-deg", "--out", "--resolution-mm", "--mode"],
    "rrr poses": ["--out", "--mode"],
    "env": [
        "--policy", "--episodes", "--seed", "--env", "--video", "--video-episodes",
        "--random-obstacles", "--action-noise", "--no-obstacle",
    ],
    "dataset": [
        "--env", "--episodes", "--noise", "--seed", "--out-dir", "--format", "--dataset-id",
    ],
    "sweep": ["--out-dir", "--backend", "--jobs", "--no-maps", "--json"],
}  # fmt: skip
"""Options of each sub-command the fuzzer combines (``demo`` only with ``--help``: minutes)."""

POSITIONALS = {"fk": 5, "ik": 4, "rrr fk": 3, "rrr ik": 3}
"""Numeric positionals of the kinematics commands."""


@dataclass(frozen=True)
class CliOutcome:
    """One fuzzed run: its arguments, exit code, stderr, and what the checks found."""

    argv: tuple[str, ...]
    code: int
    err: str
    problems: tuple[str, ...]


def make_sandbox(root: Path) -> dict[str, Path]:
    """Files the fuzzer points at inside ``root``: task files, a folder, a FIFO, a link."""
    root.mkdir(parents=True, exist_ok=True)
    paths = {
        "arm_task": root / "arm.toml",
        "evil_task": root / "evil.toml",
        "rrr_task": root / "rrr.toml",
        "folder": root / "folder",
        "fifo": root / "pipe.mp4",
        "garbage": root / "garbage.toml",
    }
    paths["arm_task"].write_text(short_arm_task())
    paths["evil_task"].write_text(short_arm_task("../../escaped"))
    paths["rrr_task"].write_text(short_rrr_task())
    paths["folder"].mkdir(exist_ok=True)
    if not paths["fifo"].exists():
        os.mkfifo(paths["fifo"])
    paths["garbage"].write_bytes(b"\x00\xff[[[poses\n" * 3)
    return paths


def _path_tokens(sandbox: dict[str, Path]) -> list[str]:
    tokens = [str(p) for p in sandbox.values()]
    tokens += ["missing.toml", "out", "out/clip.mp4", "clip.mp4", "x.avi", "plot.png", "/dev/null"]
    return tokens


def random_argv(rng: random.Random, sandbox: dict[str, Path]) -> list[str]:
    """One argument set: a sub-command, its positionals, and 0-4 options with values."""
    command = rng.choice([*FLAGS, "demo", "", "bogus"])
    argv = command.split() if command else []
    if command == "demo":
        return [*argv, "--help"]
    paths = _path_tokens(sandbox)
    pool = NUMBERS + WORDS + paths
    if command in POSITIONALS:
        n = POSITIONALS[command] + rng.choice([0, 0, 0, -1, 1])
        argv += [rng.choice(NUMBERS[:12]) if rng.random() < 0.6 else rng.choice(pool)
                 for _ in range(max(n, 0))]  # fmt: skip
    elif command == "sweep":  # never a valid sweep file: a sweep runs thousands of runs
        argv.append(rng.choice(paths))
    elif command == "view":  # a report that play wrote in the sandbox, or anything else
        reports = ["videos/short_quintic.json", "videos/short_rrr_quintic.json"]
        argv.append(rng.choice([*reports, *paths]))
    elif command in ("traj", "play", "plan"):
        task = rng.choice([sandbox["arm_task"]] * 4 + [sandbox["evil_task"], sandbox["rrr_task"]])
        argv.append(str(task) if rng.random() < 0.9 else rng.choice(paths))
    for _ in range(rng.randint(0, 4)):
        flags = FLAGS.get(command, ["--help"])
        flag = rng.choice(flags)
        argv.append(flag)
        if rng.random() < 0.8:
            argv.append(rng.choice(pool))
    if command == "play" and "--out" not in argv and rng.random() < 0.8:
        argv.append("--no-video")  # keep most runs short; some still film
    if command in ("env", "dataset", "sweep"):
        many = command != "sweep" and "--episodes" not in argv
        argv += ["--episodes", "1", "--quiet"] if many else ["--quiet"]
    if command == "plan" and "--time-limit-s" not in argv:
        argv += ["--time-limit-s", "1"]  # a blocked plan fails in a second
    if command == "workspace" and "--samples" not in argv:
        argv += ["--samples", "2000"]
    return argv


def argument_sets(seed: int, count: int, sandbox: dict[str, Path]) -> Iterator[list[str]]:
    """``count`` seeded argument sets."""
    rng = random.Random(seed)
    for _ in range(count):
        yield random_argv(rng, sandbox)


def _snapshot(root: Path, exclude: Path) -> set[Path]:
    return {p for p in root.rglob("*") if not p.is_relative_to(exclude)}


def check_run(argv: Sequence[str], sandbox_root: Path, outside: Path) -> CliOutcome:
    """Run ``lynxsim ARGV`` in-process with the sandbox as working folder and check it.

    Args:
        argv: The arguments.
        sandbox_root: Working folder of the run; every output must land inside.
        outside: A folder around the sandbox that must stay as it is, but for the
            sandbox itself (e.g. its parent: ``../escaped`` would land there).
    """
    before_outside = _snapshot(outside, sandbox_root)
    out, err = io.StringIO(), io.StringIO()
    problems: list[str] = []
    cwd = Path.cwd()
    os.chdir(sandbox_root)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                code = lynxsim_main(list(argv))
            except SystemExit as exc:
                code = exc.code if isinstance(exc.code, int) else -1
            except BaseException as exc:  # the finding itself
                code = -1
                problems.append(f"escaped {type(exc).__name__}: {exc}")
    finally:
        os.chdir(cwd)
    text = err.getvalue()
    if code not in (0, 1, 2):
        problems.append(f"exit code {code}")
    if code != 0 and text.count("\n") != 1:
        problems.append(f"stderr has {text.count(chr(10))} lines: {text[:300]!r}")
    if "Traceback" in text:
        problems.append("traceback on stderr")
    printed = out.getvalue()
    for token in sorted(argv, key=len, reverse=True):  # a file named "nan" is no finding
        printed = printed.replace(token, "")
    if code == 0 and any(w in printed for w in ("Infinity", "NaN", " nan", " inf")):
        problems.append("non-finite value printed with exit 0")
    partial = [p for p in sandbox_root.rglob("*") if ".tmp." in p.name]
    if partial:
        problems.append(f"partial files left: {partial}")
        for p in partial:
            p.unlink()
    after_outside = _snapshot(outside, sandbox_root)
    if after_outside != before_outside:
        problems.append(f"wrote outside the sandbox: {after_outside ^ before_outside}")
    return CliOutcome(tuple(argv), code, text, tuple(problems))


def main() -> int:
    """Run the campaign; returns the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=2000, help="argument sets (default 2000)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the generator")
    args = parser.parse_args()
    codes: collections.Counter[int] = collections.Counter()
    commands: collections.Counter[str] = collections.Counter()
    failures = []
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        outer = Path(tmp)
        root = outer / "sandbox"
        sandbox = make_sandbox(root)
        for i, argv in enumerate(argument_sets(args.seed, args.runs, sandbox)):
            outcome = check_run(argv, root, outer)
            codes[outcome.code] += 1
            commands[" ".join(a for a in argv[:2] if not a.startswith(("-", "/")))[:20]] += 1
            if outcome.problems:
                failures.append(outcome)
            if (i + 1) % 200 == 0:
                print(f"{i + 1} runs, {len(failures)} failures", file=sys.stderr)
    elapsed = time.perf_counter() - start
    print(f"runs {args.runs} (seed {args.seed}) in {elapsed:.0f} s")
    print("exit codes: " + ", ".join(f"{c}: {n}" for c, n in sorted(codes.items())))
    print("commands: " + ", ".join(f"{c or '(none)'}: {n}" for c, n in commands.most_common(12)))
    print(f"runs breaking a rule: {len(failures)}")
    for f in failures:
        print(f"  lynxsim {' '.join(repr(a) for a in f.argv)}: {'; '.join(f.problems)}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
