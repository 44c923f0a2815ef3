"""Print the success-vs-noise table (docs/gym_envs.md) of the scripted pick-and-place expert.

For each env id and each scene kind (the report's cylinder; ``random_obstacles=(1, 3)``)
and each action noise (:mod:`lynxsim.envs.noise`), the expert runs seeded episodes
(seeds 0, 1, ...) through :func:`lynxsim.envs.evaluate`: success at the last step,
episodes with arm-obstacle contact, and the wall and CPU time with the load average
(the machine is shared: timings are only comparable within one run).

    python tools/expert_noise_table.py [--env LynxPickAndPlace-v2 ...] [--episodes 100]
        [--noise 0 0.05 0.1 0.15 0.2]
"""

from __future__ import annotations

import argparse
import os
import time

import lynxsim.envs
from lynxsim.envs import evaluate

SCENES = (("cylinder", {}), ("random (1, 3)", {"random_obstacles": (1, 3)}))
"""Scene kinds: name and ``gym.make`` arguments."""


def main() -> None:
    """Print the table (markdown)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--env", nargs="+", default=[lynxsim.envs.PICK_AND_PLACE_V2_ID])
    parser.add_argument("--episodes", type=int, default=100)
    parser.add_argument("--noise", type=float, nargs="+", default=[0.0, 0.05, 0.1, 0.15, 0.2])
    args = parser.parse_args()
    print("| env | scene | action noise | success | contact episodes | wall / CPU [s] | load |")
    print("|---|---|---|---|---|---|---|")
    for env_id in args.env:
        for scene, kwargs in SCENES:
            for noise in args.noise:
                wall, cpu = time.perf_counter(), time.process_time()
                summary = evaluate(
                    env_id, "expert", args.episodes, 0, env_kwargs=kwargs, action_noise=noise
                )
                wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
                ok = sum(e.success for e in summary.episodes)
                contact = sum(e.collision_steps > 0 for e in summary.episodes)
                load = "{:.1f} {:.1f} {:.1f}".format(*os.getloadavg())
                print(
                    f"| {env_id} | {scene} | {noise:g} | {100 * ok / args.episodes:.0f} % "
                    f"| {contact} | {wall:.0f} / {cpu:.0f} | {load} |",
                    flush=True,
                )


if __name__ == "__main__":
    main()
