#!/usr/bin/env python3
"""The co-simulation example (examples/cosimulation/wheelset_curve_entry.py, issue 20 point 4):
runs it once on a short track and checks physical numbers of its result, not only that it runs.

Usage (ctest api.cosimulation): cosimulation_test.py <examples dir>, the built module on
PYTHONPATH.
"""
import math
import os
import sys
import tempfile
import unittest

EXAMPLES = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(
    os.path.dirname(__file__), "..", "..", "examples")
sys.path.insert(0, os.path.join(EXAMPLES, "cosimulation"))

import numpy as np  # noqa: E402

import wheelset_curve_entry as cosim  # noqa: E402

# The example's defaults, so the README's figure is this run: 2 m tangent, 15 m transition and
# 30 m of curve, R 800 m at 20 m/s, dt 5 ms: 471 steps.
ARGS = []


class CoSimulation(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.args = cosim.parse_args(ARGS + ["--out", tempfile.mkdtemp(prefix="rw_cosim_")])
        cls.r, cls.p = cosim.simulate(cls.args)
        cls.files = cosim.write_outputs(cls.args, cls.r, cls.p)
        cls.track = cls.r["track"]

    def last(self, name, fraction=0.1):
        """The values of the last `fraction` of the curve's steps."""
        s = self.r["s_m"]
        keep = s >= self.track.end - fraction * (self.track.end - self.track.s2)
        return self.r[name][keep]

    def test_tangent_track_keeps_the_centred_wheelset_centred(self):
        # Mirror-symmetric wheels and rails: the lateral forces of the two wheels cancel to
        # rounding (the left wheel is solved on the mirrored geometry), so nothing moves.
        on_tangent = self.r["s_m"] <= self.track.s1
        self.assertGreater(on_tangent.sum(), 5)
        self.assertLess(np.abs(self.r["y_m"][on_tangent]).max(), 1e-9)
        self.assertLess(np.abs(self.r["F_Y_N"][on_tangent]).max(), 1e-3 * 60e3)

    def test_the_wheelset_settles_in_the_curve(self):
        # Steady curving at the end: over the last 3 m the lateral velocity is below 10 % of the
        # mean rate at which the transition moved the wheelset out (y over the transition's 0.5 s;
        # what remains is the decaying yaw oscillation, about 2 Hz, visible in the figure), and y
        # varies by less than 2 %.
        y = self.last("y_m")
        transition_s = (self.track.s2 - self.track.s1) / self.args.speed
        self.assertLess(np.abs(self.last("ydot_m_s")).max(), 0.1 * y.mean() / transition_s)
        self.assertLess(np.ptp(y), 0.02 * abs(y.mean()))

    def test_it_steers_toward_pure_rolling(self):
        # A wheelset held on the centre line would have longitudinal creepages of -+ b0 / R
        # (the outer wheel goes further: core/contact/wheelset_contact.h); the soft yaw
        # stiffness (2 MN m/rad) lets it move outward (+Y, the high rail) until the rolling-radius
        # difference takes most of that up (Redtenbacher): the remaining difference of the wheels'
        # creepages must be below 10 % of 2 b0 / R. What remains carries the yaw spring's moment
        # (Kpsi psi = 2 f11 b0 dxi / 2, a few hundred N m): measured 1.7 % at these springs.
        y = self.last("y_m").mean()
        self.assertGreater(y, 0.5e-3)  # outward, toward the high rail
        self.assertLess(y, 6e-3)  # on the tread, not the flange
        b0 = 0.5 * np.mean(self.last("right_contact_Y_m") - self.last("left_contact_Y_m"))
        curve_creepage = 2.0 * b0 * self.track.kappa
        residual = np.mean(self.last("right_xi") - self.last("left_xi"))
        self.assertLess(abs(residual), 0.1 * curve_creepage)
        # A freely rolling axle: the wheels' longitudinal forces cancel (railwear's axle-force
        # tolerance is 1e-6 mu F_n, 0.04 N here; the net force on the rail also has the
        # pressure's small x part, so 1 N).
        self.assertLess(np.abs(self.r["right_F_X_N"] + self.r["left_F_X_N"]).max(), 1.0)
        # Tread contact on both wheels at the end: small contact angles.
        self.assertLess(np.abs(self.last("right_angle_rad")).max(), math.radians(15))

    def test_forces_balance_the_suspension_at_steady_state(self):
        # Newton's law with the accelerations gone: the contact's lateral force equals the
        # lateral spring's (the unbalanced force is zero at the balanced cant) and the contact's
        # yaw moment the yaw spring's, to 2 % of the spring force (the remaining transient).
        Ky, Kpsi = self.r["K"]
        F_spring = Ky * self.last("y_m")
        np.testing.assert_allclose(self.last("F_Y_N"), F_spring, rtol=0.02,
                                   atol=0.02 * np.abs(F_spring).max())
        M_spring = Kpsi * self.last("psi_rad")
        np.testing.assert_allclose(self.last("M_z_Nm"), M_spring, rtol=0.05,
                                   atol=0.05 * np.abs(M_spring).max())

    def test_accumulated_wear_is_archards_law_on_the_cells(self):
        # The worn area of the depth fields (both rails) equals Archard's law evaluated in Python
        # on every step's cells (k p |v| / (H V) dx ds, the same weights): the depth field
        # conserves each patch's worn area to rounding (wear/pass_depth.h). 1e-9: rounding of
        # some 10^4 cells per step over the steps.
        area = self.r["right_worn_area_m2"][-1] + self.r["left_worn_area_m2"][-1]
        self.assertGreater(area, 0.0)
        self.assertLess(abs(area - self.r["expected_worn_area_m2"]),
                        1e-9 * self.r["expected_worn_area_m2"])
        # Nothing accumulates before the circular curve.
        before = self.r["s_m"] < self.track.s2
        self.assertEqual(self.r["right_worn_area_m2"][before].max(), 0.0)

    def test_outputs_are_written(self):
        steps = np.loadtxt(self.files[0])
        self.assertEqual(steps.shape, (self.r["t_s"].size, len(self.r["names"])))
        depth = np.loadtxt(self.files[1])
        self.assertEqual(depth.shape[1], 4)
        with open(self.files[2]) as f:
            self.assertIn("cosim_steps.dat", f.read())


if __name__ == "__main__":
    unittest.main()
