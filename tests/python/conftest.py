"""Shared fixtures of the Python tests: the C++ reference values
(cpp_reference.cpp, written before the tests run) and the scene modules,
found on PYTHONPATH as ctest sets it (tests/CMakeLists.txt)."""

import json
import os

import numpy as np
import pytest


def _decode(v):
    if isinstance(v, str):
        return float.fromhex(v)
    if isinstance(v, list):
        return [_decode(e) for e in v]
    if isinstance(v, dict):
        return {k: _decode(e) for k, e in v.items()}
    return v


@pytest.fixture(scope="session")
def reference():
    """The C++ API's results, exactly (hexadecimal floats)."""
    path = os.environ.get("FLANGE_CPP_REFERENCE")
    if not path:
        pytest.fail("FLANGE_CPP_REFERENCE is not set: run the tests through ctest")
    with open(path) as f:
        return _decode(json.load(f))


def as_array(v):
    return np.array(v, dtype=float)
