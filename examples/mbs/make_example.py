#!/usr/bin/env python3
"""Writes examples/mbs/curve_r600_mbs.csv: a SYNTHETIC MBS time history for `railwear traffic import`.

It is not the output of a vehicle-dynamics code nor of railwear's own curving: it is made up, to
show the CSV format (docs/mbs_import.md) with plausible magnitudes. A bogie vehicle (two bogies of
two wheelsets, semi-wheelbase 1.25 m) runs at 21 m/s through a steady left curve of R 600 m with
100 mm cant, sampled every dt = 0.01 s for 40 steps: 4 wheelsets x 2 wheels x 40 steps = 320 rows.

Each wheelset holds a steady curving state (lateral displacement toward the high rail, yaw, roll,
wheel loads, longitudinal creepage, the MBS's lateral and longitudinal forces on the rail), chosen
by hand in the pattern of quasi-static curving: the leading wheelset of each bogie is near flange
contact on the high rail with its nose turned outward (yaw ~ +a/R = +2.1 mrad), the trailing one
lies nearer the centre with negative yaw. Gaussian noise (fixed seed) stands for track
irregularities. Signs follow railwear's track frame: y, yaw and roll positive toward the high rail.

The weight of each row is the distance run in its time step, weight_m = dt * V.

    python3 examples/mbs/make_example.py      # rewrites examples/mbs/curve_r600_mbs.csv
"""
import pathlib
import random

SEED = 15
STEPS = 40
DT_S = 0.01
SPEED_M_S = 21.0
MU = 0.35

# wheelset: (y [mm], yaw [mrad], roll [mrad], Q high [N], Q low [N], xi high, xi low,
#            Fy high [N], Fy low [N]); Fy = lateral force on the rail, toward its field side.
STATES = [
    (6.4, 2.4, -2.3, 80500.0, 76500.0, -0.0021, 0.0018, 38000.0, 9000.0),   # bogie 1, leading
    (2.1, -1.1, -0.4, 79000.0, 78000.0, -0.0006, 0.0005, 6000.0, -4000.0),  # bogie 1, trailing
    (6.1, 2.2, -2.1, 80200.0, 76800.0, -0.0019, 0.0016, 35000.0, 8500.0),   # bogie 2, leading
    (1.8, -1.3, -0.3, 78800.0, 78200.0, -0.0005, 0.0004, 5000.0, -4500.0),  # bogie 2, trailing
]
# noise standard deviations: y [mm], yaw [mrad], roll [mrad], Q [N], xi, V [m/s], Fy [N]
NOISE = (0.25, 0.2, 0.1, 1500.0, 0.0002, 0.03, 2000.0)


def main():
    rng = random.Random(SEED)
    out = pathlib.Path(__file__).with_name("curve_r600_mbs.csv")
    lines = [
        "# SYNTHETIC MBS time history (made up, not from a vehicle-dynamics code): "
        "examples/mbs/make_example.py, seed 15.",
        "# A bogie vehicle at 21 m/s in a steady left curve R 600 m, cant 100 mm; dt 0.01 s, "
        "40 steps, 4 wheelsets x 2 wheels.",
        "# Track frame: y, yaw, roll positive toward the high (outer, right) rail; weight_m = dt * V.",
        "weight_m,side,V_m_s,y_mm,yaw_mrad,roll_mrad,Q_N,xi,mu,mbs_Fy_N,mbs_Fx_N",
    ]
    for _ in range(STEPS):
        speed = SPEED_M_S + rng.gauss(0.0, NOISE[5])
        for y, yaw, roll, q_high, q_low, xi_high, xi_low, fy_high, fy_low in STATES:
            # One wheelset state per time step: both wheels share y, yaw and roll.
            dy = rng.gauss(0.0, NOISE[0])
            y_t = y + dy
            yaw_t = yaw + rng.gauss(0.0, NOISE[1])
            roll_t = roll + rng.gauss(0.0, NOISE[2])
            for side, q, xi, fy in (("high", q_high, xi_high, fy_high),
                                    ("low", q_low, xi_low, fy_low)):
                q_t = q + rng.gauss(0.0, NOISE[3])
                xi_t = xi + rng.gauss(0.0, NOISE[4])
                fy_t = fy + 4000.0 * dy + rng.gauss(0.0, NOISE[6])
                fx_t = -MU * q_t * xi_t / 0.004 if abs(xi_t) < 0.004 else -MU * q_t
                lines.append(f"{DT_S * speed:.4f},{side},{speed:.3f},{y_t:.3f},{yaw_t:.3f},"
                             f"{roll_t:.3f},{q_t:.1f},{xi_t:.5f},{MU},{fy_t:.1f},{fx_t:.1f}")
    out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
