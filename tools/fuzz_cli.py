"""Fuzz campaign over the command line, in-process (see ``tests/fuzz/cli_cases.py``).

    python tools/fuzz_cli.py --runs 2000 --seed 0

Prints the counts by exit code and every run that broke a rule (with its
arguments, to reproduce with ``lynxsim ARGS``); exits 1 if any did.
"""

from __future__ import annotations

import argparse
import collections
import os
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.fuzz.cli_cases import argument_sets, check_run, make_sandbox


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
