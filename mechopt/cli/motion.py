"""``mechopt motion DESIGN_DIR [--path ...] [--cycle-time S] ...``: the chosen design of
``mechopt design`` run along a timed motion: actuator positions, rates, efforts, power.

Runs :func:`mechopt.workflows.motion.run_motion`, which writes ``motion.csv``,
``bodies.json``, ``motion.json`` and ``motion.png`` into ``--out`` (default the design's
folder). Prints one line: the peak and RMS effort and the peak rate of each actuator.
"""
from __future__ import annotations

NAME = "motion"


def add_parser(subparsers):
    """Register ``motion``."""
    from mechopt.core.motion import PROFILES
    from mechopt.core.rigid_bodies import MATERIALS

    mp = subparsers.add_parser(NAME, help="run a design along a timed motion: actuator efforts, rates, power")
    mp.add_argument("design_dir", help="folder written by mechopt design (design.json, run.json)")
    mp.add_argument("--path", default="pick-place",
                    help="pick-place (default: 25 up, 305 across, 25 down [mm] scaled to the task's "
                         "width), segment:X0,Y0,X1,Y1 [unit of the design] or csv:FILE (columns x, y "
                         "[unit]; a cubic spline through them)")
    mp.add_argument("--profile", default="cycloidal",
                    help=f"timing of each piece, from rest to rest: {', '.join(PROFILES)} (default cycloidal)")
    mp.add_argument("--cycle-time", type=float, default=0.5, help="duration of the whole path [s] (default 0.5)")
    mp.add_argument("--accel-fraction", type=float, default=1.0 / 3.0,
                    help="trapezoidal, s-curve: fraction of each piece's time spent accelerating, "
                         "in (0, 0.5] (default 1/3)")
    mp.add_argument("--jerk-fraction", type=float, default=0.25,
                    help="s-curve: fraction of the acceleration time at constant jerk, in [0, 0.5] "
                         "(default 0.25)")
    mp.add_argument("--samples", type=int, default=401, help="time samples along the motion (default 401)")
    mp.add_argument("--masses", default=None, metavar="FILE.json",
                    help="mass model: {\"law\": {material (" + ", ".join(sorted(MATERIALS)) + "), density "
                         "[kg/m^3], outer, wall [m], motor, payload, carriage [kg], rotor_inertia "
                         "[kg m^2], gear_ratio}, \"bodies\": {name: {mass [kg], com [fraction], inertia "
                         "[kg m^2]}}} (default: 20 x 20 x 2 mm aluminium tubes; the gantry: Wu 2008 Table 2)")
    mp.add_argument("--gravity", default="down",
                    help="down (default: -y, 9.80665 m/s^2; Wu's 9.8 for the gantry's Table 2), off "
                         "(a horizontal table) or GX,GY [m/s^2] in the plane")
    mp.add_argument("--max-speed", default=None, metavar="W[,W2]",
                    help="actuator rate limit(s) drawn and checked [rad/s or m/s]")
    mp.add_argument("--max-torque", default=None, metavar="T[,T2]",
                    help="peak effort limit(s) drawn and checked [N m or N]")
    mp.add_argument("--max-rms-torque", default=None, metavar="T[,T2]",
                    help="RMS effort limit(s) (rated torque) drawn and checked [N m or N]")
    mp.add_argument("--actuator", default=None, metavar="SPEC|FILE",
                    help="the motors' datasheet, as for mechopt design --actuator (rated_torque, peak_torque "
                         "[N m], max_speed [rad/s or 3000rpm], gear_ratio, rotor_inertia [kg m^2]; inline or "
                         ".json/.toml): the reflected rotor inertia I_r N^2 enters the dynamics and max_speed/N, "
                         "peak x N and rated x N are the limits not given")
    mp.add_argument("--out", default=None, help="output folder (default: DESIGN_DIR)")


def run(args) -> int:
    """Compute and write the motion, print one line."""
    from mechopt.workflows.motion import run_motion

    s = run_motion(args.design_dir, args.out, args.path, args.profile, args.cycle_time,
                   args.samples, args.masses, args.gravity, args.max_speed, args.max_torque,
                   args.max_rms_torque, args.accel_fraction, args.jerk_fraction, args.actuator)
    print("; ".join(f"actuator {i + 1}: peak {s['tau_peak'][i]:.4g}, RMS {s['tau_rms'][i]:.4g} "
                    f"(N m or N), peak rate {s['qd_peak'][i]:.4g}" for i in (0, 1))
          + f"; moving mass {s['moving_mass']:.4g} kg; within limits: {s['within_limits']}")
    return 0
