"""MuJoCo's exact ``mj_geomDistance``, callable from compiled (numba) code.

:func:`geom_distance` is a numba intrinsic that calls MuJoCo's own C function
through its address (:func:`geom_distance_address`, found in the library the
``mujoco`` package loaded), with the model and data passed as their addresses
(``MjModel._address``, ``MjData._address``): the same function, the same
arguments and so the same result as ``mujoco.mj_geomDistance`` from Python,
without the Python call around each one. The address is an argument, not a
constant, so that the numba functions calling it can be cached on disk.
"""

from __future__ import annotations

import ctypes
import functools
from pathlib import Path

import mujoco
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

__all__ = ["geom_distance", "geom_distance_address"]

_LIBRARIES = ("libmujoco.so*", "libmujoco*.dylib", "mujoco.dll")
"""Where the ``mujoco`` package keeps its shared library (Linux, macOS, Windows)."""


@functools.cache
def geom_distance_address() -> int:
    """Address of MuJoCo's ``mj_geomDistance`` in the library the ``mujoco`` package loaded.

    Raises:
        RuntimeError: The package's shared library is not found.
    """
    folder = Path(mujoco.__file__).parent
    found = sorted(p for pattern in _LIBRARIES for p in folder.glob(pattern))
    if not found:
        raise RuntimeError(f"MuJoCo's shared library is not in {folder}")
    library = ctypes.CDLL(str(found[0]))  # already loaded by the package: the same copy
    address = ctypes.cast(library.mj_geomDistance, ctypes.c_void_p).value
    if address is None:
        raise RuntimeError("MuJoCo's library has no mj_geomDistance")
    return int(address)


@intrinsic
def geom_distance(typingctx, function, model, data, geom1, geom2, distmax):  # type: ignore[no-untyped-def]  # numba
    """``mj_geomDistance(model, data, geom1, geom2, distmax, NULL)`` [m] (compiled code only).

    Args (all numba values):
        function: :func:`geom_distance_address`.
        model: ``MjModel._address``.
        data: ``MjData._address`` (its geom poses are read).
        geom1, geom2: The geom ids.
        distmax: The cut-off [m].
    """
    sig = types.float64(function, model, data, geom1, geom2, distmax)
    wanted = (types.intp, types.intp, types.intp, types.int32, types.int32, types.float64)

    def codegen(context, builder, signature, args):  # type: ignore[no-untyped-def]
        address, m, d, g1, g2, cut = (
            context.cast(builder, value, given, want)
            for value, given, want in zip(args, signature.args, wanted, strict=True)
        )
        pointer = ir.IntType(8).as_pointer()
        int32, double = ir.IntType(32), ir.DoubleType()
        kind = ir.FunctionType(double, [pointer, pointer, int32, int32, double, pointer])
        call = builder.inttoptr(address, kind.as_pointer())
        null = ir.Constant(pointer, None)
        m, d = builder.inttoptr(m, pointer), builder.inttoptr(d, pointer)
        return builder.call(call, [m, d, g1, g2, cut, null])

    return sig, codegen
