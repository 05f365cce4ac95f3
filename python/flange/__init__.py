"""flange from Python: what every compiled scene module shares.

A scene module (built by CMake's flange_add_python_module or
flange_urdf_python_module, docs/python.md) imports this package for its
exceptions and result types, so that ``except flange.SimulationError`` catches
the failures of every scene.
"""

from dataclasses import dataclass, field
import math

import numpy as np

__all__ = ["Error", "ParameterError", "UnknownNameError", "SimulationError", "Trajectory", "EnsembleResult"]


class Error(Exception):
    """Base of every flange exception (C++ flange::error)."""


class ParameterError(Error, ValueError):
    """A value no scene can take: a bad parameter, a state of the wrong
    shape or dtype, a non-finite time (C++ flange::parameter_error)."""


class UnknownNameError(ParameterError, KeyError):
    """A joint, parameter or field name the scene does not have; the message
    names the closest one."""

    def __str__(self):  # KeyError would quote the message
        return str(self.args[0]) if self.args else ""


class SimulationError(Error):
    """A breakdown during a simulation (C++ flange::simulation_error): a
    non-finite state or derivative, a singular mass matrix, a spent budget of
    evaluations, a step size that collapsed, a loop that came open.

    time:   when it happened
    state:  the state then (numpy array, x = (q, v))
    reason: what went wrong, without the time and the state
    """

    def __init__(self, message, time=math.nan, state=None, reason=""):
        super().__init__(message)
        self.time = time
        self.state = np.asarray(state if state is not None else [], dtype=float)
        self.reason = reason


@dataclass
class Trajectory:
    """simulate()'s result: the states at the requested times."""

    t: np.ndarray  #: the requested times, shape (T,)
    x: np.ndarray  #: the state at each, shape (T, n_state)
    steps: int  #: accepted steps
    rhs_evals: int  #: derivative evaluations

    def __len__(self):
        return len(self.t)


@dataclass
class EnsembleResult:
    """ensemble()'s result, case by case (k cases, T times)."""

    t: np.ndarray  #: the times, shape (T,)
    x: np.ndarray  #: the states, shape (k, T, n_state); NaN after a case's failure
    ok: np.ndarray  #: whether each case ran to the end, shape (k,)
    reason: list  #: why a case failed ("" if it did not)
    fail_time: np.ndarray  #: when it failed (NaN if it did not)
    fail_state: np.ndarray  #: the last accepted state before the failure, shape (k, n_state)
    steps: np.ndarray  #: accepted steps per case
    rhs_evals: np.ndarray  #: derivative evaluations per case
    parameters: dict = field(default_factory=dict)  #: each parameter's value per case
    recorded: dict = field(default_factory=dict)  #: each recorder's value per case (NaN: never seen, or failed)

    def __len__(self):
        return len(self.ok)

    @property
    def failed(self):
        """How many cases failed."""
        return int(np.count_nonzero(~self.ok))
