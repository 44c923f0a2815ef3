"""The physics of many arm envs stepped together, on MuJoCo's native threads.

:class:`EnvBatch` steps the scenes of N envs (:class:`~lynxsim.sim.arm.env_scene.EnvScene`,
each with its own ``MjModel`` as its episodes edit it) in one
:class:`mujoco.batch.Batch` call, the GIL released, on ``nthread`` threads.
The batch keeps one ``MjData`` per env (``persistent``); after a step each
scene's own ``MjData`` receives the batch's whole data (``get_data``: state,
positions, contacts), so everything an env reads after a step (observation,
contacts, frames) is what ``mj_step`` on that data would have left, bit for bit
(MuJoCo's batch is bit-identical to a loop over one ``MjData`` per simulation at
any thread count, and :meth:`EnvScene.touching_obstacle` is the one contact test).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from concurrent.futures import Future, ThreadPoolExecutor

import mujoco
import numpy as np
from mujoco import batch as mjbatch

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import count
from lynxsim.sim.arm.env_scene import EnvScene
from lynxsim.sim.stepping.overlap import cpu_count

__all__ = ["MAX_THREADS", "EnvBatch"]

MAX_THREADS = 256
"""Most threads a batch may be asked for."""

_STATE = mujoco.mjtState.mjSTATE_INTEGRATION
_NO_STAGE = int(mujoco.mjtStage.mjSTAGE_NONE)


class EnvBatch:
    """N env scenes of one layout, stepped in one native call.

    Args:
        scenes: The envs' scenes (models of one layout: compiled from one spec,
            their parameters edited per episode).
        nthread: Threads stepping, the caller's included (None: one per CPU,
            never more than one per scene).

    Raises:
        InvalidInputError: No scene, scenes of different layouts, or ``nthread``
            not an integer in 1..:data:`MAX_THREADS`.
    """

    def __init__(self, scenes: Sequence[EnvScene], nthread: int | None = None) -> None:
        if not scenes:
            raise InvalidInputError("an env batch needs at least one scene")
        self._scenes = tuple(scenes)
        first = self._scenes[0].model
        for s in self._scenes[1:]:
            m = s.model
            if (m.nq, m.nv, m.nu, m.ngeom, m.nbody) != (
                first.nq,
                first.nv,
                first.nu,
                first.ngeom,
                first.nbody,
            ):
                raise InvalidInputError("the scenes of an env batch must share one layout")
        threads = cpu_count() if nthread is None else count(nthread, "nthread", 1, MAX_THREADS)
        self.nthread = min(threads, len(self._scenes))
        """Threads stepping, the caller's included."""
        self._batch = mjbatch.Batch(first, len(self._scenes), self.nthread, persistent=True)
        self._batch.set_models([s.model for s in self._scenes])
        self._rows = self._batch.state
        self._helper: ThreadPoolExecutor | None = None

    def __len__(self) -> int:
        return len(self._scenes)

    def load(self, ids: Sequence[int]) -> None:
        """Start scenes ``ids`` afresh in the batch (after their env's reset), models read anew.

        The batch's data of each is reset (``mj_resetData``: its warnings
        cleared, as the scene's own reset clears the scene's); every model is
        read again (an episode edits its model: obstacles, randomisation).
        """
        if ids:
            self._batch.reset(np.asarray(ids, dtype=np.intp), stage=_NO_STAGE)
            self._batch.set_models([s.model for s in self._scenes])

    def simulate(self, ids: Sequence[int], steps: int, *, every_step: bool) -> list[bool]:
        """Step scenes ``ids`` by ``steps`` physics steps from the state of their data.

        What :meth:`EnvScene.simulate <lynxsim.sim.arm.env_scene.EnvScene.simulate>`
        does for one scene, for all of them in native calls: each scene's whole
        integration state (its controls included) goes into the batch, and after
        the steps each scene's data is what that call would have left.

        Args:
            ids: The scenes to step.
            steps: Physics steps.
            every_step: Test the contacts after every step (each step a native
                call), else only after the last.

        Returns:
            Per scene of ``ids``: whether the arm or the cube touched an obstacle.
        """
        if not ids:
            return []
        index = np.asarray(ids, dtype=np.intp)
        scenes, rows, batch = self._scenes, self._rows, self._batch
        for i in ids:
            mujoco.mj_getState(scenes[i].model, scenes[i].data, rows[i], _STATE)
        hits = [False] * len(ids)
        for _ in range(steps if every_step else 1):
            batch.step(index, nstep=1 if every_step else steps)
            for k, i in enumerate(ids):
                scene = scenes[i]
                batch.get_data(i, scene.data)
                hits[k] = scene.touching_obstacle() or hits[k]
        return hits

    def pipeline(
        self,
        ids: Sequence[int],
        steps: int,
        *,
        every_step: bool,
        after: Callable[[Sequence[int], list[bool]], None],
        chunks: int,
    ) -> None:
        """:meth:`simulate` scenes ``ids`` in chunks, their Python work overlapping the stepping.

        The scenes' controls are written beforehand (by the caller, for all of
        them at once). A helper thread steps each chunk (the GIL released while
        MuJoCo steps) while this thread hands the stepped ones to ``after``
        (with their contact verdicts), in order. Every scene ends as
        :meth:`simulate` leaves it.

        Args:
            ids: The scenes to step.
            steps: Physics steps.
            every_step: As :meth:`simulate`.
            after: Called with each chunk's scenes and verdicts once stepped.
            chunks: How many chunks (at most one per scene; 1: no helper thread).
        """
        size = -(-len(ids) // max(1, min(chunks, len(ids)))) if ids else 1
        parts = [list(ids[k : k + size]) for k in range(0, len(ids), size)]
        if len(parts) <= 1:
            for part in parts:
                after(part, self.simulate(part, steps, every_step=every_step))
            return
        if self._helper is None:
            self._helper = ThreadPoolExecutor(1, thread_name_prefix="lynxsim-env-batch")
        helper = self._helper
        running: list[Future[list[bool]]] = []
        try:
            for part in parts:
                running.append(helper.submit(self.simulate, part, steps, every_step=every_step))
            for part, stepped in zip(parts, running, strict=True):
                after(part, stepped.result())
        finally:
            for stepped in running:
                stepped.cancel()
            for stepped in running:
                if not stepped.cancelled():
                    stepped.exception()  # wait: no chunk steps once this returns

    def close(self) -> None:
        """Stop the helper thread, if any (idempotent)."""
        if self._helper is not None:
            self._helper.shutdown()
            self._helper = None
