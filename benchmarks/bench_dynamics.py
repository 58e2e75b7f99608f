"""Cost of the dynamics requirement: evaluations per second of the peak actuator effort
along a timed motion (issue 29), one core.

    python benchmarks/bench_dynamics.py

For each mechanism: the pick-and-place cycle (25 up, 305 across, 25 down, scaled to a
300 x 200 task) timed by a cycloidal profile in 0.5 s, sampled at 101 and 401 times;
one evaluation = build the mechanism + mass model (default law) + inverse dynamics +
the peak (:func:`mechopt.analysis.dynamics.peak_torque`), the motion sampled once.
Also the closed-form box speed/force limits (:mod:`mechopt.core.actuators`) in poses/s.
"""
from __future__ import annotations

import time

import numpy as np


def _rate(fn, seconds=1.0):
    n, t0 = 0, time.perf_counter()
    times = []
    while time.perf_counter() - t0 < seconds:
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
        n += 1
    return 1.0 / min(times)  # the fastest run: the cost without the other loads of a shared machine


def main():
    from mechopt import Biglide, Bipod, FiveBar
    from mechopt.analysis.dynamics import mass_model, peak_torque
    from mechopt.core import motion as mo
    from mechopt.core.actuators import guaranteed_force, guaranteed_speed
    from mechopt.mechanisms.asymmetric_five_bar import AsymmetricFiveBar
    from mechopt.mechanisms.gantry import Gantry

    cases = {
        "five-bar": (lambda: FiveBar(200.0, 300.0, 80.0), (-150, 150, 200, 400)),
        "asymmetric-five-bar": (lambda: AsymmetricFiveBar(200.0, 300.0, 220.0, 310.0, 80.0), (-150, 150, 200, 400)),
        "biglide": (lambda: Biglide(300.0, 500.0, -800.0, 800.0), (-150, 150, 0, 200)),
        "bipod": (lambda: Bipod(400.0, 150.0, 700.0), (50, 350, 200, 400)),
        "gantry": (lambda: Gantry(350.0, 600.0, 900.0, q_min=-700.0), (-150, 150, 0, 200)),
    }
    for n in (101, 401):
        for name, (make, box) in cases.items():
            m = mo.timed_motion(mo.pick_and_place_path(box), 0.5, "cycloidal", n)

            def one():
                mech = make()
                peak_torque(mech, m, mass_model(mech, length_unit=1e-3), length_unit=1e-3)
            one()
            print(f"peak torque along the pick-and-place cycle, {name}, {n} samples: "
                  f"{_rate(one):.0f} evaluations/s")
    J = FiveBar(200.0, 300.0, 80.0).jacobian(np.random.default_rng(1).uniform(-100, 100, 100_000),
                                             np.random.default_rng(2).uniform(250, 350, 100_000))
    r = _rate(lambda: (guaranteed_speed(J, 3.0), guaranteed_force(J, 8.0)))
    print(f"box speed and force limits: {r * J.shape[0]:.3g} poses/s")


if __name__ == "__main__":
    main()
