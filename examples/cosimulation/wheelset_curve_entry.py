#!/usr/bin/env python3
"""A wheelset through a curve entry, co-simulated with railwear (issue 20 point 4).

A small vehicle-dynamics model in Python calls the railwear module (the C API of librailwear,
docs/library.md) once per time step, as an MBS code calls its contact model, and accumulates the
rail wear of every step with Problem.accumulate.

The model (an approximation, stated here and in the README's "Co-simulation from Python"):
  - One wheelset, S1002 wheels on UIC60 rails inclined 1:40 at 1435 mm gauge, in a frame that
    moves along the track centre line at the speed V: the wheelset's degrees of freedom are its
    lateral displacement y (toward +Y, the right rail, which is the high rail of the curve) and
    its yaw psi against the local track tangent (core/notation.md). Roll, bounce and the axle's
    spin are not degrees of freedom: each wheel carries its static load Q (railwear balances it
    vertically), and the axle rolls freely: railwear finds the pitch velocity at which the two
    wheels' longitudinal creep forces cancel (longitudinal_force_N = 0; the spin's own time
    constant, I_y V / (2 f11 r0^2), is about a millisecond, far below the step).
  - Primary suspension: per axlebox a longitudinal stiffness kx and a lateral one ky, the boxes
    b1 to either side, to a frame that follows the track centre line along its tangent (a bogie
    frame that curves perfectly): a lateral stiffness 2 ky and a yaw stiffness 2 kx b1^2.
  - Track: tangent, then a transition whose curvature and cant grow linearly with distance, then
    a circular curve of radius R turning toward -Y (railwear's curve convention). The cant
    balances V^2/R by default, so the unbalanced lateral force m (V^2 kappa - g phi) is zero;
    --cant-mm sets another cant (the load transfer it would cause is not modelled).
  - Contact forces and creepages come from railwear (kind AUTO, draft grid, FASTSIM tractions),
    with the wheelset's lateral and yaw velocity and the track curvature in the state.
    The patches' spin moments are left out of the yaw moment.
  - Time integration: semi-implicit (linearly implicit) Euler with a fixed step dt. The creep
    forces' dependence on the step's own velocities is taken implicitly through Kalker's linear
    creep coefficients of the last step's patches (C = G a b c_22 / V laterally, G a b c_11 b^2 / V
    in yaw; Kalker's c_ij at nu = 0.28, a b = area / pi), which keeps the step stable at dt = 5 ms
    where explicit Euler needs < 3 ms; the positions follow with the new velocities (symplectic).
    The steady state does not depend on these coefficients.
  - Wear: Archard's law (k = 1e-4, rail hardness 2.6 GPa). Every step in the circular curve
    accumulates V dt / L_curve passes, so the depth field at the end is the mean depth one
    wheelset pass removes from the curve's rails; the transition's and tangent's steps are not
    accumulated.

Outputs in --out: cosim_steps.dat (one line per step), cosim_depth.dat (the depth fields),
cosim.gp (a gnuplot script) and, with --plot, cosim.png drawn by gnuplot.

Run:  PYTHONPATH=build/api/python python3 examples/cosimulation/wheelset_curve_entry.py \
          --out /tmp/cosim --plot
"""
import argparse
import math
import os
import shutil
import subprocess
import sys

import numpy as np

import railwear

GRAVITY_M_S2 = 9.81
SHEAR_MODULUS_PA = 210e9 / (2.0 * (1.0 + 0.28))  # steel, railwear's default material
# Kalker's creep coefficients for nu = 0.28 at a/b = 1 (Kalker 1967, table; between the nu = 0.25
# and 0.5 columns): used only for the implicit part of the step, not for any result.
KALKER_C11 = 4.3
KALKER_C22 = 3.7
ARCHARD_K = 1e-4
RAIL_HARDNESS_PA = 2.6e9


def parse_args(argv=None):
    a = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    a.add_argument("--out", default=".", help="directory for the data files and the plot")
    a.add_argument("--plot", action="store_true", help="draw cosim.png with gnuplot")
    a.add_argument("--speed", type=float, default=20.0, help="V [m/s]")
    a.add_argument("--radius-m", type=float, default=800.0, help="curve radius R [m]")
    a.add_argument("--cant-mm", type=float, default=None,
                   help="cant of the curve [mm] over a 1.5 m base; default: balanced at V")
    a.add_argument("--tangent-m", type=float, default=2.0, help="tangent track before [m]")
    a.add_argument("--transition-m", type=float, default=15.0, help="transition length [m]")
    a.add_argument("--curve-m", type=float, default=30.0, help="circular curve length [m]")
    a.add_argument("--dt", type=float, default=0.005, help="time step [s]")
    a.add_argument("--wheel-load-kN", type=float, default=60.0, help="Q per wheel [kN]")
    a.add_argument("--mass-kg", type=float, default=1500.0, help="wheelset mass [kg]")
    a.add_argument("--yaw-inertia-kgm2", type=float, default=800.0, help="wheelset I_z")
    a.add_argument("--kx-MN-m", type=float, default=1.0, help="primary kx per axlebox")
    a.add_argument("--ky-MN-m", type=float, default=0.5, help="primary ky per axlebox")
    a.add_argument("--b1-m", type=float, default=1.0, help="axlebox semi-spacing b1 [m]")
    a.add_argument("--friction", type=float, default=0.3)
    return a.parse_args(argv)


class Track:
    """Curvature [1/m] and cant angle [rad] against the distance s along the centre line."""

    def __init__(self, args):
        self.s1 = args.tangent_m
        self.s2 = self.s1 + args.transition_m
        self.end = self.s2 + args.curve_m
        self.kappa = 1.0 / args.radius_m
        cant_mm = args.cant_mm
        if cant_mm is None:  # balanced: g sin(phi) = V^2 / R
            cant_mm = 1.5e3 * args.speed ** 2 / (GRAVITY_M_S2 * args.radius_m)
        self.phi = math.asin(cant_mm * 1e-3 / 1.5)

    def ramp(self, s):
        if s <= self.s1:
            return 0.0
        if s >= self.s2:
            return 1.0
        return (s - self.s1) / (self.s2 - self.s1)

    def curvature(self, s):
        return self.kappa * self.ramp(s)

    def cant(self, s):
        return self.phi * self.ramp(s)

    def curvature_slope(self, s):  # d kappa / ds
        return self.kappa / (self.s2 - self.s1) if self.s1 < s < self.s2 else 0.0

    def in_curve(self, s):
        return s >= self.s2


def make_problem(args):
    p = railwear.Problem(railwear.PROBLEM_WHEELSET)
    p.set_profile_file(railwear.BODY_WHEEL, "builtin:S1002")
    p.set_profile_file(railwear.BODY_RAIL, "builtin:UIC60")
    p.set_geometry(rail_cant=1.0 / 40.0, rolling_radius_m=0.46)
    p.set_model(kind=railwear.MODEL_AUTO, accuracy=railwear.ACCURACY_DRAFT,
                effects=railwear.EFFECT_TANGENTIAL)
    p.set_materials({}, {"hardness_Pa": RAIL_HARDNESS_PA})
    p.set_friction(args.friction)
    p.set_wear(law=railwear.WEAR_ARCHARD, archard_k=ARCHARD_K)
    return p


def wheelset_loads(p):
    """The last calculate's forces and moment on the wheelset in the track frame, and per wheel
    the main patch's creepages: (F_Y [N], M_z [N m], per-wheel dicts, damping areas)."""
    wheels = [dict(F_X=0.0, F_Y=0.0, N=0.0, Y=0.0, xi=0.0, eta=0.0, phi=0.0, angle=0.0,
                   patches=0, area=0.0) for _ in range(2)]
    for i in range(p.get_patch_count()):
        q = p.get_patch(i)
        w = wheels[q["wheel"]]
        mirror = 1.0 if q["wheel"] == 0 else -1.0  # left rail frame: y = -Y
        f = q["force_on_rail_N"]
        fx, fy = -f[0], -mirror * f[1]  # on the wheel, track frame
        w["F_X"] += fx
        w["F_Y"] += fy
        w["M_z"] = w.get("M_z", 0.0) + q["contact_x_m"] * fy - q["contact_track_Y_m"] * fx
        w["area"] += q["area_m2"]
        w["patches"] += 1
        if q["normal_force_N"] > w["N"]:  # the main patch's creepages and position
            w.update(N=q["normal_force_N"], Y=q["contact_track_Y_m"], xi=q["creepage_xi"],
                     eta=mirror * q["creepage_eta"], phi=q["creepage_spin_per_m"],
                     angle=q["contact_angle_rad"])
    F_Y = wheels[0]["F_Y"] + wheels[1]["F_Y"]
    M_z = wheels[0].get("M_z", 0.0) + wheels[1].get("M_z", 0.0)
    return F_Y, M_z, wheels


def archard_area_per_pass(p, speed):
    """Worn area per pass [m^2] of the last calculate's patches, summed over both rails, straight
    from the cells: Archard's dz/dL = k p |v| / (H V) over dx, times ds (wear/pass_depth.h)."""
    total = 0.0
    for i in range(p.get_patch_count()):
        c = p.get_cells(i)
        xs, ss = np.unique(c["x_m"]), np.unique(c["s_m"])
        dx = xs[1] - xs[0] if xs.size > 1 else 0.0
        ds = ss[1] - ss[0] if ss.size > 1 else 0.0
        slip = np.hypot(c["slip_x_m_s"], c["slip_s_m_s"])
        total += ARCHARD_K / (RAIL_HARDNESS_PA * speed) * np.sum(c["pressure_Pa"] * slip) * dx * ds
    return total


def worn_area(p, rail):
    s, d = p.get_depth(rail)
    h = s[1] - s[0] if s.size > 1 else 0.0
    return float(np.sum(d) * h)


def set_state(p, args, track, s, y, psi, ydot, psidot):
    p.set_state(lateral_m=y, yaw_rad=psi, lateral_velocity_m_s=ydot, yaw_velocity_rad_s=psidot,
                vertical_force_N=args.wheel_load_kN * 1e3, speed_m_s=args.speed,
                longitudinal_force_N=0.0, curvature_per_m=track.curvature(s))


def simulate(args, log=None):
    """Runs the time loop; returns a dict of NumPy arrays (one entry per step) and the handle."""
    track = Track(args)
    p = make_problem(args)
    V, dt, m, Iz = args.speed, args.dt, args.mass_kg, args.yaw_inertia_kgm2
    Ky = 2.0 * args.ky_MN_m * 1e6
    Kpsi = 2.0 * args.kx_MN_m * 1e6 * args.b1_m ** 2
    y = psi = ydot = psidot = 0.0
    C_y = C_psi = 0.0  # implicit creep damping of the last step
    rows = []
    expected_area = 0.0  # Archard's worn area from the cells, summed with the same weights
    s, t = 0.0, 0.0
    steps = int(math.ceil(track.end / (V * dt)))
    for n in range(steps + 1):
        kappa = track.curvature(s)
        set_state(p, args, track, s, y, psi, ydot, psidot)
        status = p.calculate()
        if status != railwear.OK:
            raise RuntimeError(f"step {n} (s = {s:.2f} m): calculate returned {status}")
        F_Y, M_z, w = wheelset_loads(p)
        if track.in_curve(s):
            passes = V * dt / (track.end - track.s2)
            p.accumulate(passes)
            expected_area += passes * archard_area_per_pass(p, V)
        # The suspension, the unbalanced force in the moving frame (centrifugal toward +Y, the
        # cant's share of gravity toward the low rail) and, in yaw against the tangent, which
        # turns toward -Y at V kappa, the tangent's angular acceleration -V^2 dkappa/ds.
        F_unbalanced = m * (V ** 2 * kappa - GRAVITY_M_S2 * math.sin(track.cant(s)))
        F = F_Y - Ky * y + F_unbalanced
        M = M_z - Kpsi * psi + Iz * V ** 2 * track.curvature_slope(s)
        rows.append([t, s, kappa, y, psi, ydot, psidot, F_Y, M_z,
                     w[0]["F_X"], w[0]["F_Y"], w[1]["F_X"], w[1]["F_Y"],
                     w[0]["xi"], w[0]["eta"], w[1]["xi"], w[1]["eta"],
                     w[0]["angle"], w[1]["angle"], w[0]["Y"], w[1]["Y"],
                     worn_area(p, 0), worn_area(p, 1)])
        if log and n % 50 == 0:
            log(f"t {t:5.2f} s  s {s:6.2f} m  y {y * 1e3:6.3f} mm  psi {psi * 1e3:7.4f} mrad  "
                f"F_Y {F_Y * 1e-3:7.2f} kN  M_z {M_z * 1e-3:7.2f} kN m")
        if n == steps:
            break
        # Kalker's linear creep damping of this step's patches: G a b c / V per wheel.
        b0 = 0.5 * abs(w[0]["Y"] - w[1]["Y"])
        ab = sum(wh["area"] for wh in w) / math.pi
        C_y = SHEAR_MODULUS_PA * ab * KALKER_C22 / V
        C_psi = SHEAR_MODULUS_PA * ab * KALKER_C11 * b0 ** 2 / V
        ydot += dt * F / (m + dt * C_y)
        psidot += dt * M / (Iz + dt * C_psi)
        y += dt * ydot
        psi += dt * psidot
        s += V * dt
        t += dt
    names = ["t_s", "s_m", "kappa_per_m", "y_m", "psi_rad", "ydot_m_s", "psidot_rad_s", "F_Y_N",
             "M_z_Nm", "right_F_X_N", "right_F_Y_N", "left_F_X_N", "left_F_Y_N", "right_xi",
             "right_eta", "left_xi", "left_eta", "right_angle_rad", "left_angle_rad",
             "right_contact_Y_m", "left_contact_Y_m", "right_worn_area_m2", "left_worn_area_m2"]
    data = np.array(rows)
    out = {name: data[:, k] for k, name in enumerate(names)}
    out["names"] = names
    out["expected_worn_area_m2"] = expected_area
    out["track"] = track
    out["K"] = (Ky, Kpsi)
    return out, p


def write_outputs(args, result, p):
    os.makedirs(args.out, exist_ok=True)
    names = result["names"]
    steps = os.path.join(args.out, "cosim_steps.dat")
    np.savetxt(steps, np.column_stack([result[n] for n in names]), fmt="%.9g",
               header=" ".join(names))
    depth = os.path.join(args.out, "cosim_depth.dat")
    s0, d0 = p.get_depth(0)
    s1, d1 = p.get_depth(1)
    np.savetxt(depth, np.column_stack([s0, d0, s1, d1]), fmt="%.9g",
               header="right_s_m right_depth_per_pass_m left_s_m left_depth_per_pass_m")
    track = result["track"]
    script = os.path.join(args.out, "cosim.gp")
    with open(script, "w") as f:
        f.write(GNUPLOT.format(s1=track.s1, s2=track.s2))
    if args.plot:
        if shutil.which("gnuplot") is None:
            raise SystemExit("--plot needs the program 'gnuplot', which is not on PATH; install "
                             "gnuplot (e.g. apt-get install gnuplot-nox) or plot the .dat files")
        subprocess.run(["gnuplot", "cosim.gp"], cwd=args.out, check=True)
    return steps, depth, script


# Columns of cosim_steps.dat: 1 t, 2 s, 3 kappa, 4 y, 5 psi, 6 ydot, 7 psidot, 8 F_Y, 9 M_z,
# 10/11 right F_X/F_Y, 12/13 left F_X/F_Y, 14/15 right xi/eta, 16/17 left xi/eta, ...
GNUPLOT = """\
set terminal pngcairo size 1200,900 noenhanced
set output 'cosim.png'
set multiplot layout 2,2 title 'S1002/UIC60 wheelset through a curve entry, railwear per step'
set grid
set key top left
set arrow from {s1},graph 0 to {s1},graph 1 nohead dt 2
set arrow from {s2},graph 0 to {s2},graph 1 nohead dt 2
set xlabel 'distance along the track [m]'
set ylabel 'y [mm], psi [mrad]'
plot 'cosim_steps.dat' u 2:($4*1e3) w l lw 2 t 'lateral displacement y', \\
     '' u 2:($5*1e3) w l lw 2 t 'yaw psi'
set ylabel 'creep force on the wheel [kN]'
plot 'cosim_steps.dat' u 2:($10*1e-3) w l t 'right (high) F_X', '' u 2:($11*1e-3) w l t 'right F_Y', \\
     '' u 2:($12*1e-3) w l t 'left (low) F_X', '' u 2:($13*1e-3) w l t 'left F_Y'
set ylabel 'creepage [1e-3]'
plot 'cosim_steps.dat' u 2:($14*1e3) w l t 'right xi', '' u 2:($15*1e3) w l t 'right eta', \\
     '' u 2:($16*1e3) w l t 'left xi', '' u 2:($17*1e3) w l t 'left eta'
unset arrow
set xlabel 'rail profile arc length [mm]'
set ylabel 'mean depth per 1000 passes in the curve [nm]'
plot 'cosim_depth.dat' u ($1*1e3):($2*1e12) w l lw 2 t 'right (high) rail', \\
     '' u ($3*1e3):($4*1e12) w l lw 2 t 'left (low) rail'
unset multiplot
"""


def main(argv=None):
    args = parse_args(argv)
    result, p = simulate(args, log=print)
    files = write_outputs(args, result, p)
    print("wrote " + ", ".join(files) + (" and cosim.png" if args.plot else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
