"""What Python costs over C++ for a compiled scene module: the tutorial's arm
(examples/spatial_arm.hpp, module `spatial_arm`, built with the C++ timing
loops of include/flange/python/timing.hpp), timed in one process.

    build/python/python3 benchmarks/python/bench_python.py

Each line: python <what> python_ns=<x> cpp_ns=<y> ratio=<x/y>, medians.
  derivative_call  one derivative(t, x, out) from Python against one C++ call:
                   the difference is the Python overhead per call
  derivative_batch derivative(t, X, out) over 10^5 states against the same loop in C++
  simulate         simulate(x0, times) of a 10 s run (dopri5, 1e-8, 1001 output times)
                   against C++ simulate() on the same times
"""

import statistics
import time

import numpy as np

import spatial_arm as m


def median_ns(f, repeats, inner=1):
    t = []
    for _ in range(repeats):
        a = time.perf_counter_ns()
        for _ in range(inner):
            f()
        t.append((time.perf_counter_ns() - a) / inner)
    return statistics.median(t)


def line(what, py, cpp):
    print(f"python {what} python_ns={py:.0f} cpp_ns={cpp:.0f} ratio={py / cpp:.3f}", flush=True)


def main():
    x = m.initial_state(elbow=0.6, shoulder={"q": 0.2, "v": 0.5})
    out = np.empty_like(x)
    d = m.derivative
    inner = 20000
    py = median_ns(lambda: d(0.0, x, out), 15, inner)
    cpp = m._time_derivative(0.0, np.tile(x, (inner, 1)), 15) / inner
    line("derivative_call", py, cpp)
    print(f"python derivative_call overhead_ns={py - cpp:.0f}", flush=True)

    rng = np.random.default_rng(1)
    X = rng.uniform(-1, 1, size=(100_000, m.n_state))
    OUT = np.empty_like(X)
    py = median_ns(lambda: d(0.0, X, OUT), 9)
    cpp = m._time_derivative(0.0, X, 9)
    line("derivative_batch", py, cpp)

    times = np.linspace(0.0, 10.0, 1001)
    py = median_ns(lambda: m.simulate(x, times), 9)
    cpp = m._time_simulate(x, times, "dopri5", 1e-8, 9)
    line("simulate", py, cpp)


if __name__ == "__main__":
    main()
