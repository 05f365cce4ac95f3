"""A parameter study of the buffered crane from Python: an ensemble over the
cart controller's gain kp and the load's mass, run by flange's C++ ensemble
engine (on every core where oneTBB is installed), then the swing and the
settling time worked out with numpy and plotted with matplotlib.

    build/python/python3 examples/python/crane_study.py [--png out.png]

The scene is examples/python/crane_scene.hpp (flange/models/controlled_crane.hpp),
compiled once into the module `crane`; every case is a run-time value.
"""

import argparse
import math
import sys
import time

import numpy as np

import crane
import flange


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--png", help="write the plot here (else show it)")
    args = ap.parse_args()

    # 20 gains × 10 loads = 200 cases, each 10 s, sampled every 20 ms
    kp, m_load = np.meshgrid(np.linspace(2.0, 40.0, 20), np.linspace(0.1, 2.0, 10), indexing="ij")
    times = np.linspace(0.0, 10.0, 501)
    x0 = crane.initial_state(rail=-0.5, pivot=-math.pi / 2)  # load hanging, buffer unstretched
    start = time.perf_counter()
    # the swing's peak from every step and the dense output (not only the samples)
    res = crane.ensemble({"controller.kp": kp.ravel(), "m_load": m_load.ravel()}, times, x0=x0,
                         recorders={"swing": ("max_abs", "pivot.q", -math.pi / 2)})
    seconds = time.perf_counter() - start
    if res.failed:
        for i in np.flatnonzero(~res.ok):
            print(f"case {i} failed at t = {res.fail_time[i]}: {res.reason[i]}", file=sys.stderr)
        return 1

    # the load's swing: its angle from the vertical (φ = θ − π/2), recorded; the cart's settling: the last
    # time it is more than 1 cm from where it comes to rest (the controller's pull against the
    # buffer's: the last sample)
    rail = crane.joint_layout["rail"]["q"]
    swing = res.recorded["swing"]
    s = res.x[:, :, rail][..., 0]
    off = np.abs(s - s[:, -1:]) > 0.01
    settle = np.where(off.any(axis=1), times[np.where(off, np.arange(len(times)), 0).max(axis=1)], 0.0)
    print(f"crane study: {len(res)} cases in {seconds:.2f} s ({res.rhs_evals.sum()} derivative evaluations, "
          f"threads: {crane.threaded_ensembles})")
    best = np.argmin(settle + 10 * (swing > 0.1))
    print(f"  fastest settling with a swing under 0.1 rad: kp = {res.parameters['controller.kp'][best]:.1f}, "
          f"m_load = {res.parameters['m_load'][best]:.2f} kg, {settle[best]:.2f} s, swing {swing[best]:.3f} rad")

    import matplotlib

    if args.png:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    shape = kp.shape
    c = a.contourf(kp, m_load, swing.reshape(shape), levels=20, cmap="viridis")
    fig.colorbar(c, ax=a, label="largest swing [rad]")
    a.set(xlabel="cart gain kp [N/m]", ylabel="load mass [kg]", title="swing of the load")
    c = b.contourf(kp, m_load, settle.reshape(shape), levels=20, cmap="magma")
    fig.colorbar(c, ax=b, label="settling time [s]")
    b.set(xlabel="cart gain kp [N/m]", ylabel="load mass [kg]", title="cart within 1 cm of its rest")
    if args.png:
        fig.savefig(args.png, dpi=90)
        print(f"  plot: {args.png}")
    else:
        plt.show()
    return 0


if __name__ == "__main__":
    sys.exit(main())
