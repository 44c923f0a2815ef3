"""The real-arm package stays pure: no MuJoCo, no pyserial until a port opens."""

from __future__ import annotations

import subprocess
import sys


def test_importing_lynxsim_real_loads_neither_mujoco_nor_pyserial():
    code = (
        "import sys, lynxsim.real, lynxsim.real.driver, lynxsim.real.compare, lynxsim.cli; "
        "print('mujoco' in sys.modules, 'serial' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "False"]
