"""Input checks (:mod:`lynxsim.inputs`): wrong types are typed errors of both kinds."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm import ik_one
from lynxsim.arm.motion import generate
from lynxsim.errors import InvalidTypeError


@pytest.mark.parametrize("value", ["abc", None, {"x": 1}, [1.0, "a", 2.0], 1j, np.array([True])])
def test_wrong_types_are_type_errors_and_value_errors(value):
    with pytest.raises(InvalidTypeError) as info:
        ik_one(value, 0.0)
    assert isinstance(info.value, TypeError)
    assert isinstance(info.value, ValueError)
    with pytest.raises(InvalidTypeError):
        generate("quintic", value)
