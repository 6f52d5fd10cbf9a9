#!/usr/bin/env python3
"""Writes the 21 scene files of the Manchester contact benchmark, case A-2.2.

Source: Shackleton & Iwnicki, "Comparison of wheel-rail contact codes for railway vehicle
simulation: an introduction to the Manchester Contact Benchmark and initial results", Vehicle
System Dynamics 46 (2008) 129-149; the inputs as encoded in CONTACT's examples (Apache-2.0), whose
author iterated roll and pitch velocity so that the wheelset balances. The table is the one in
../shared/reference/README.md, section 5b.

    python3 examples/manchester/make_cases.py      # rewrites examples/manchester/case_NN.toml
"""
import pathlib

# case: (y_ws [mm], yaw [mrad], roll [rad], pitch velocity [rad/s])
CASES = [
    (0.0, 0.0, 0.00000000, -4.34811810),
    (0.5, 1.2, -0.00002304, -4.34741340),
    (1.0, 2.4, -0.00005049, -4.34657520),
    (1.5, 3.6, -0.00008103, -4.34624400),
    (2.0, 4.8, -0.00011280, -4.34591970),
    (2.5, 6.0, -0.00014570, -4.34556270),
    (3.0, 7.2, -0.00018030, -4.34515030),
    (3.5, 8.4, -0.00021680, -4.34466880),
    (4.0, 9.6, -0.00025570, -4.34409300),
    (4.5, 10.8, -0.00029770, -4.34337150),
    (5.0, 12.0, -0.00035540, -4.33536370),
    (5.5, 13.2, -0.00047770, -4.33188640),
    (6.0, 14.4, -0.00062720, -4.32937180),
    (6.5, 15.6, -0.00437600, -4.27488340),
    (7.0, 16.8, -0.00639300, -4.26356290),
    (7.5, 18.0, -0.00764200, -4.25757470),
    (8.0, 19.2, -0.00860600, -4.25348570),
    (8.5, 20.4, -0.00940800, -4.25032450),
    (9.0, 21.6, -0.01010113, -4.24775610),
    (9.5, 22.8, -0.01071386, -4.24556650),
    (10.0, 24.0, -0.01126431, -4.24363750),
]

TEMPLATE = """\
# Description:
#   Manchester contact benchmark, case A-2.2, case {n} of 21 (Shackleton & Iwnicki, Vehicle
#   System Dynamics 46 (2008) 129-149; inputs as in ../shared/reference/README.md, section 5b):
#   the benchmark's S1002 wheelset on its UIC60 rails (already canted 1:40), displaced
#   {y} mm to the right and yawed by {yaw} mrad, with the roll and pitch velocity that balance it.
#   G = 82 000 MPa and nu = 0.28 for both bodies, mu = 0.30, 10 kN per wheel, V = 2 m/s,
#   0.2 mm cells. Written by make_cases.py beside this file; needs ../shared/data/profiles/.
#
# Sample run:
#   railwear contact examples/manchester/case_{n:02d}.toml

[scene]
name = "Manchester benchmark A-2.2, case {n}: y_ws {y} mm, yaw {yaw} mrad"
effects = ["normal", "tangential"]

[model]
geometry = "conformal"     # the curved grid with the half-space kernel, which the project's
kernel = "boussinesq"      # FEM check puts within 2 % of CalculiX (docs/fem_contact_cases.md)
cell_mm = [0.2, 0.2]

[materials]
wheel = {{ E_MPa = 209920, nu = 0.28 }}   # G = E / (2 (1 + nu)) = 82 000 MPa
rail  = {{ E_MPa = 209920, nu = 0.28 }}

[wheel]
profile = "../../../shared/data/profiles/MBench_S1002_v3.prw"
rolling_radius_mm = 460

[rail]
profile = "../../../shared/data/profiles/MBench_UIC60_v3.prr"

[track]
gauge_mm = 1435
gauge_height_mm = 14

[wheelset]
flange_back_distance_mm = 1360
flange_back_position_mm = -70
lateral_displacement_mm = {y}
yaw_mrad = {yaw}
roll_rad = {roll:.8f}
pitch_velocity_rad_s = {omega:.8f}
vertical_load_per_wheel_N = 10000
speed_m_s = 2.0

[load]
friction = 0.3
"""

here = pathlib.Path(__file__).resolve().parent
for n, (y, yaw, roll, omega) in enumerate(CASES, start=1):
    (here / f"case_{n:02d}.toml").write_text(
        TEMPLATE.format(n=n, y=y, yaw=yaw, roll=roll, omega=omega))
print(f"wrote {len(CASES)} scenes to {here}")
