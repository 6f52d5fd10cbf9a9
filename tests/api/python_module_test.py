"""The Python module `railwear` (api/python): the same names as the C API, NumPy arrays out,
errors as railwear.Error. Parity: the gauge-corner example set up from Python gives the numbers
`railwear contact examples/gauge_corner.toml --json` writes, bit for bit (the CLI equals the C
API, tests/api/parity_test.cpp; the module only translates). Run by ctest as
    python3 tests/api/python_module_test.py RAILWEAR_BINARY EXAMPLES_DIR
with PYTHONPATH holding the built module."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

import railwear

RAILWEAR = sys.argv[1] if len(sys.argv) > 1 else "railwear"
EXAMPLES = sys.argv[2] if len(sys.argv) > 2 else "examples"
MM = 1e-3  # the scene reader's mm -> m factor (core/numerics/units.h kMm)


def gauge_corner(**model):
    """examples/gauge_corner.toml through the module, in the scene reader's own arithmetic."""
    p = railwear.Problem(railwear.PROBLEM_WHEEL)
    p.set_profile_file(railwear.BODY_WHEEL, "builtin:S1002")
    p.set_profile_file(railwear.BODY_RAIL, "builtin:UIC60")
    p.set_geometry(rolling_radius_m=460 * MM, rail_cant=1.0 / 40.0)
    steel = {"youngs_modulus_Pa": 210000 * 1e6, "poisson_ratio": 0.28}
    p.set_materials(steel, steel)
    p.set_model(kind=railwear.MODEL_CONFORMAL, accuracy=railwear.ACCURACY_STANDARD, **model)
    p.set_state(lateral_m=-4.0 * MM, vertical_force_N=100000.0)
    return p


class PythonModule(unittest.TestCase):
    def test_the_module_equals_the_cli_bit_for_bit(self):
        out = subprocess.run([RAILWEAR, "contact", EXAMPLES + "/gauge_corner.toml", "--json", "-"],
                             check=True, capture_output=True, text=True).stdout
        cli = json.loads(out)["patches"]
        p = gauge_corner()
        self.assertEqual(p.calculate(), railwear.OK)
        self.assertEqual(p.get_patch_count(), len(cli))
        for i, q in enumerate(cli):
            patch = p.get_patch(i)
            self.assertEqual(patch["normal_force_N"], q["normal_force_N"])
            self.assertEqual(patch["p_max_Pa"] * 1e-6, q["p_max_MPa"])
            self.assertEqual(patch["area_m2"] * 1e6, q["area_mm2"])
            self.assertEqual(patch["cells_in_contact"], q["cells_in_contact"])
            # The wheel frame (API 1.2): without yaw or roll, the rail frame's point less the
            # wheel's lateral shift (tests/api/wheel_frame_test.cpp).
            self.assertEqual(patch["contact_wheel_y_m"], patch["contact_y_m"] - (-4.0 * MM))
            self.assertEqual(patch["contact_wheel_x_m"], patch["contact_x_m"])
            cells = p.get_cells(i)
            self.assertIsInstance(cells["pressure_Pa"], np.ndarray)
            self.assertEqual(len(cells["pressure_Pa"]), patch["cells"])
            self.assertEqual(int(np.count_nonzero(cells["pressure_Pa"] > 0)),
                             patch["cells_in_contact"])

    def test_the_strict_normal_solver_equals_the_cli_with_the_scene_key(self):
        # API 1.5: rw_model's normal_criterion and normal_tolerance are the scene's [model]
        # normal_criterion and normal_tolerance (docs/speed.md "The 4-digit defaults"): the
        # gauge-corner example with the key, through the CLI and through the module, bit for bit.
        with open(EXAMPLES + "/gauge_corner.toml") as f:
            text = f.read()
        cases = [('normal_criterion = "gap-residual"\n',
                  {"normal_criterion": railwear.NORMAL_GAP_RESIDUAL}),
                 ('normal_criterion = "gap-residual"\nnormal_tolerance = 1e-12\n',
                  {"normal_criterion": railwear.NORMAL_GAP_RESIDUAL, "normal_tolerance": 1e-12})]
        p_max = {}
        for key, model in cases:
            with tempfile.TemporaryDirectory() as tmp:
                scene = os.path.join(tmp, "strict.toml")
                with open(scene, "w") as f:
                    f.write(text.replace("[model]\n", "[model]\n" + key, 1))
                out = subprocess.run([RAILWEAR, "contact", scene, "--json", "-"], check=True,
                                     capture_output=True, text=True).stdout
            cli = json.loads(out)
            self.assertEqual(cli["model"]["normal_criterion"], "gap-residual")
            p = gauge_corner(**model)
            self.assertEqual(p.calculate(), railwear.OK)
            self.assertEqual(p.get_patch_count(), len(cli["patches"]))
            for i, q in enumerate(cli["patches"]):
                patch = p.get_patch(i)
                self.assertEqual(patch["normal_force_N"], q["normal_force_N"])
                self.assertEqual(patch["p_max_Pa"] * 1e-6, q["p_max_MPa"])
                self.assertEqual(patch["area_m2"] * 1e6, q["area_mm2"])
            p_max[key] = p.get_patch(0)["p_max_Pa"]
        # The switch acts: the default (4 digits) stops earlier than the strict setting.
        default = gauge_corner()
        default.calculate()
        self.assertNotEqual(default.get_patch(0)["p_max_Pa"], p_max[cases[0][0]])
        with self.assertRaises(railwear.Error) as e:
            gauge_corner(normal_tolerance=0.5)
        self.assertEqual(e.exception.status_name, "RW_ERROR_INVALID_VALUE")
        self.assertIn("rw_model.normal_tolerance = 0.5", str(e.exception))
        # The exact tangential solver's stop (API 1.5, [model] tangential_tolerance) by the same
        # name: checked as the C API checks it (its parity with the CLI: tests/api/parity_test.cpp).
        with self.assertRaises(railwear.Error) as e:
            gauge_corner(tangential_tolerance=0.5)
        self.assertEqual(e.exception.status_name, "RW_ERROR_INVALID_VALUE")
        self.assertIn("rw_model.tangential_tolerance = 0.5", str(e.exception))
        self.assertEqual(gauge_corner(tangential_tolerance=1e-9).calculate(), railwear.OK)

    def test_the_warm_start_as_the_c_api_has_it(self):
        # API 1.5: set_warm_start is rw_set_warm_start (tests/api/warm_start_test.cpp). The first
        # calculate is the cold one bit for bit; a nearby position (+0.05 mm) stays within the
        # standard preset's measured errors of a cold handle's (area 7.3 %, p_max twice its
        # 3.1 %: contact_warm_start_test.cpp's named tolerances); switched off, the calculates are
        # cold again, bit for bit; a bool is its only argument.
        warm, cold = gauge_corner(), gauge_corner()
        warm.set_warm_start(True)
        for p in (warm, cold):
            self.assertEqual(p.calculate(), railwear.OK)
        for i in range(cold.get_patch_count()):
            self.assertEqual(warm.get_patch(i), cold.get_patch(i))
        for p in (warm, cold):
            p.set_state(lateral_m=-4.05 * MM, vertical_force_N=100000.0)
            self.assertEqual(p.calculate(), railwear.OK)
        self.assertEqual(warm.get_patch_count(), cold.get_patch_count())
        for i in range(cold.get_patch_count()):
            w, c = warm.get_patch(i), cold.get_patch(i)
            self.assertAlmostEqual(w["area_m2"] / c["area_m2"], 1.0, delta=0.073)
            self.assertAlmostEqual(w["p_max_Pa"] / c["p_max_Pa"], 1.0, delta=0.062)
        # It started warm: a fallback would be the cold call bit for bit (measured here: p_max
        # 0.26 % and the area 0.22 % apart).
        self.assertNotEqual(warm.get_patch(0)["p_max_Pa"], cold.get_patch(0)["p_max_Pa"])
        warm.set_warm_start(False)
        for p in (warm, cold):
            p.set_state(lateral_m=-4.1 * MM, vertical_force_N=100000.0)
            self.assertEqual(p.calculate(), railwear.OK)
        for i in range(cold.get_patch_count()):
            self.assertEqual(warm.get_patch(i), cold.get_patch(i))
        with self.assertRaises(TypeError):
            warm.set_warm_start("yes")

    def test_profile_points_from_numpy(self):
        p = railwear.Problem()
        y = np.linspace(-0.02, 0.02, 41)
        p.set_profile_points(railwear.BODY_WHEEL, np.column_stack([y, -(0.3 - np.sqrt(0.3**2 - y**2))]))
        p.set_profile_points(railwear.BODY_RAIL, np.column_stack([y, 0.3 - np.sqrt(0.3**2 - y**2)]))
        p.set_model(kind=railwear.MODEL_HERTZ)
        p.set_state(vertical_force_N=50e3)
        self.assertEqual(p.calculate(), railwear.OK)
        self.assertGreater(p.get_patch(0)["p_max_Pa"], 0.0)
        with self.assertRaises(ValueError):
            p.set_profile_points(railwear.BODY_WHEEL, np.zeros((5, 3)))

    def test_hertz_tread_path_and_its_fallback(self):
        # RW_MODEL_HERTZ with rolling contact (API 1.3): on the crown the fast tread path, at
        # -10.4 mm the fallback to auto (core/contact/hertz_tread.h), each saying so.
        p = railwear.Problem()
        p.set_profile_file(railwear.BODY_WHEEL, "builtin:S1002")
        p.set_profile_file(railwear.BODY_RAIL, "builtin:UIC60")
        p.set_geometry(rail_cant=1 / 40)
        p.set_model(kind=railwear.MODEL_HERTZ, accuracy=railwear.ACCURACY_DRAFT,
                    effects=railwear.EFFECT_TANGENTIAL)
        p.set_friction(0.3)
        p.set_state(lateral_m=-20e-3, yaw_rad=5e-3, vertical_force_N=100e3, speed_m_s=20.0)
        self.assertEqual(p.calculate(), railwear.OK)
        model, reason = p.get_patch_model(0)
        self.assertEqual(model, "hertz")
        self.assertTrue(reason.startswith("fast tread path: one Hertzian patch"), reason)
        p.set_state(lateral_m=-10.4e-3, yaw_rad=5e-3, vertical_force_N=100e3, speed_m_s=20.0)
        self.assertEqual(p.calculate(), railwear.OK)
        model, reason = p.get_patch_model(0)
        self.assertNotEqual(model, "hertz")
        self.assertTrue(reason.startswith("fast tread path not valid: non-Hertzian patch"), reason)

    def test_errors_are_raised_with_status_and_message(self):
        p = railwear.Problem()
        with self.assertRaises(railwear.Error) as e:
            p.set_friction(-1.0)
        self.assertEqual(e.exception.status, 3)
        self.assertEqual(e.exception.status_name, "RW_ERROR_INVALID_VALUE")
        self.assertIn("friction = -1", str(e.exception))
        with self.assertRaises(railwear.Error) as e:
            p.calculate()
        self.assertEqual(e.exception.status_name, "RW_ERROR_CALL_ORDER")
        with self.assertRaises(TypeError):
            p.set_state(lateral_mm=4.0)  # an unknown field, named
        with self.assertRaises(railwear.Error):
            railwear.Problem(7)

    def test_pressure_limit(self):
        # A limit below the elastic peak caps every cell (the C API's rw_set_pressure_limit).
        p = railwear.Problem()
        p.set_profile_file(railwear.BODY_WHEEL, "circle:300")
        p.set_profile_file(railwear.BODY_RAIL, "circle:300")
        p.set_model(kind=railwear.MODEL_HALFSPACE, accuracy=railwear.ACCURACY_DRAFT)
        p.set_state(vertical_force_N=50e3)
        p.calculate()
        elastic = p.get_patch(0)["p_max_Pa"]
        p.set_pressure_limit(railwear.PRESSURE_LIMIT_VALUE, 0.8 * elastic)
        p.calculate()
        self.assertLessEqual(p.get_cells(0)["pressure_Pa"].max(), 0.8 * elastic * (1 + 1e-12))
        with self.assertRaises(railwear.Error) as e:
            p.set_pressure_limit(railwear.PRESSURE_LIMIT_VALUE)  # no value
        self.assertEqual(e.exception.status_name, "RW_ERROR_INVALID_VALUE")

    def test_accumulate(self):
        p = railwear.Problem()
        p.set_profile_file(railwear.BODY_WHEEL, "builtin:S1002")
        p.set_profile_file(railwear.BODY_RAIL, "builtin:UIC60")
        p.set_geometry(rail_cant=1.0 / 40.0)
        steel = {"youngs_modulus_Pa": 210e9, "poisson_ratio": 0.28}
        p.set_materials(steel, dict(steel, hardness_Pa=2.6e9))
        p.set_model(accuracy=railwear.ACCURACY_DRAFT, effects=railwear.EFFECT_TANGENTIAL)
        p.set_friction(0.3)
        p.set_wear(law=railwear.WEAR_ARCHARD)
        p.set_state(lateral_m=-4e-3, vertical_force_N=100e3, speed_m_s=20.0, yaw_rad=5e-3)
        self.assertEqual(p.calculate(), railwear.OK)
        p.accumulate(1.0)
        s, one = p.get_depth(0)
        p.accumulate(1.0)
        _, two = p.get_depth(0)
        self.assertEqual(len(s), len(one))
        self.assertGreater(one.max(), 0.0)
        np.testing.assert_array_equal(two, one + one)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
