"""scripts/ape-spread against stand-ins for swlio-run and swlio-eval (stand_ins.py): every draw
runs with its own floor (draw 0 the configured one), loop closure off unless asked, the extra
arguments passed on; the APEs come back per draw with their median, the second recording's
median over the first's; a failing run is a clear error with exit status 1."""
import unittest
from pathlib import Path

from stand_ins import FAKE_EVAL, StandInTest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "ape-spread"

# swlio-run stand-in: logs its arguments; its trajectory file holds one number, the APE that
# swlio-eval will print: the recording's base (REC/base.txt) times 1 + 1000 * (floor/0.01 - 1).
FAKE_RUN = """\
#!/usr/bin/python3
import json, os, sys
a = sys.argv[1:]
rec, out, floor = a[0], a[a.index("--out") + 1], float(a[a.index("--lidar-floor-m") + 1])
with open(os.environ["FAKE_LOG"], "a") as f:
    f.write(json.dumps(a) + "\\n")
base = float(open(os.path.join(rec, "base.txt")).read())
if base < 0:
    print("swlio-run: the recording is broken", file=sys.stderr)
    sys.exit(3)
open(out, "w").write(repr(base * (1 + 1000 * (floor / 0.01 - 1))))
"""


class ApeSpread(StandInTest):
    SCRIPT = SCRIPT
    PROGRAMS = {"swlio-run": FAKE_RUN, "swlio-eval": FAKE_EVAL}
    spread = StandInTest.run_script
    runs = StandInTest.logged

    def rec(self, name, base):
        p = Path(self.tmp.name) / name
        p.mkdir()
        (p / "base.txt").write_text(str(base))
        return str(p)

    def test_draws_medians_and_ratio(self):
        a, b = self.rec("a", 0.02), self.rec("b", 0.03)
        r = self.spread("--draws", "3", a, b, "--", "--wheel", "on")
        self.assertEqual(r.returncode, 0, r.stderr)
        # Draw k's floor is 0.01 (1 + k 1e-5): the stand-in's APE is base (1 + k 0.01).
        self.assertIn(f"{a}: 0.0200 0.0202 0.0204 | median 0.0202 min 0.0200 max 0.0204",
                      r.stdout)
        self.assertIn(f"{b}: 0.0300 0.0303 0.0306 | median 0.0303", r.stdout)
        self.assertIn("| median / first's 1.50", r.stdout)
        runs = self.runs()
        self.assertEqual(len(runs), 6)
        for args in runs:
            self.assertEqual(args[args.index("--loop-closure") + 1], "off")
            self.assertEqual(args[-2:], ["--wheel", "on"])
        floors = sorted({float(x[x.index("--lidar-floor-m") + 1]) for x in runs})
        self.assertEqual(floors[0], 0.01)
        self.assertAlmostEqual(floors[2], 0.01 * (1 + 2e-5), delta=1e-15)

    def test_loop_closure_asked_for_is_kept(self):
        r = self.spread("--draws", "1", self.rec("a", 0.02), "--", "--loop-closure", "on")
        self.assertEqual(r.returncode, 0, r.stderr)
        (args,) = self.runs()
        self.assertEqual(args.count("--loop-closure"), 1)
        self.assertEqual(args[args.index("--loop-closure") + 1], "on")

    def test_a_failing_run_is_a_clear_error(self):
        r = self.spread("--draws", "2", self.rec("broken", -1))
        self.assertEqual(r.returncode, 1)
        self.assertIn("exited with 3", r.stderr)
        self.assertIn("the recording is broken", r.stderr)
        self.assertNotIn("Traceback", r.stderr)

    def test_draws_must_be_positive(self):
        r = self.spread("--draws", "0", self.rec("a", 0.02))
        self.assertEqual(r.returncode, 2)
        self.assertIn("--draws and --jobs must be at least 1", r.stderr)


if __name__ == "__main__":
    unittest.main()
