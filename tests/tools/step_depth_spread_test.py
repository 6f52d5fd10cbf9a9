#!/usr/bin/env python3
"""ctest tool.step_depth_spread: tests/tools/step_depth_spread.py on a real wear database.

Runs `railwear wear` on examples/wear_high_rail.toml for three steps (one rail, so every step's
deepest smoothed wear is the step limit) into a scratch database and checks what the tool reads:
each step's peak is the scene's max_depth_per_step_mm, the peaks sum to at least the deepest
accumulated wear, the widths and the short wave are finite and within the profile; and that a
database without step depth fields is refused with its name.
  usage: step_depth_spread_test.py RAILWEAR EXAMPLES_DIR
"""
import os
import shutil
import sqlite3
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import step_depth_spread  # noqa: E402


def main(railwear, examples):
    scene = os.path.join(examples, "wear_high_rail.toml")
    limit_mm = None
    with open(scene) as f:
        for line in f:
            if line.startswith("max_depth_per_step_mm"):
                limit_mm = float(line.split("=")[1].split("#")[0])
    assert limit_mm, f"{scene}: no max_depth_per_step_mm"
    with tempfile.TemporaryDirectory() as work:
        db = os.path.join(work, "w.sqlite")
        run = subprocess.run([railwear, "wear", scene, "--db", db, "--steps", "3", "--threads", "1"],
                             capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        rows = step_depth_spread.steps_of(db)
        assert [r["step"] for r in rows] == [1, 2, 3], rows
        for r in rows:
            # One rail: the step control puts its deepest smoothed step depth at the limit.
            assert abs(r["peak"] - limit_mm) <= 1e-9 * limit_mm, (r, limit_mm)
            assert 0.0 < r["width"] < 200.0, r
            assert 0.0 <= r["short_wave"] < 1e3 * r["deepest"], r
        # Peaks that add up can only meet or exceed the deepest point's growth.
        assert sum(r["peak"] for r in rows) >= rows[-1]["deepest"] - 1e-12, rows
        # The whole report runs on it.
        report = subprocess.run([sys.executable, step_depth_spread.__file__, db],
                                capture_output=True, text=True)
        assert report.returncode == 0, report.stderr
        assert "0-1" in report.stdout, report.stdout
        # A database without step depth fields: refused with its name.
        empty = os.path.join(work, "empty.sqlite")
        shutil.copyfile(db, empty)
        con = sqlite3.connect(empty)
        con.execute("DELETE FROM distributions WHERE kind = 'step_depth_mm'")
        con.commit()
        con.close()
        refused = subprocess.run([sys.executable, step_depth_spread.__file__, empty],
                                 capture_output=True, text=True)
        assert refused.returncode != 0 and "empty.sqlite" in refused.stderr, refused
    print("step_depth_spread: 3 steps read, peaks at the limit, refusal checked")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
