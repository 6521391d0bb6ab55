"""scripts/ape-realizations against stand-ins for swlio-sim, swlio-run and swlio-eval: each seed
makes a pair in the given world (a second scenario or the disturbances), both are run once with
loop closure off and the extra arguments; the table gives both APEs and their ratio, bold over
the bound, then the median ratio, the ratio of the sums, the largest and how many exceed it;
recordings are made once per work folder; simulator arguments for the variant alone give it
recordings of its own; a failing run is a clear error with exit status 1."""
import unittest
from pathlib import Path

from stand_ins import FAKE_EVAL, StandInTest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "ape-realizations"

# swlio-sim stand-in: logs its arguments; a recording whose ape.txt holds the APE the run will
# give: 0.01 × seed on the base, times 1.1 (odd seed) or 1.5 (even) with a variant. Seed 99
# fails.
FAKE_SIM = """\
#!/usr/bin/python3
import json, os, sys
a = sys.argv[1:]
with open(os.environ["FAKE_LOG"], "a") as f:
    f.write(json.dumps(["sim"] + a) + "\\n")
out, seed = a[a.index("--out") + 1], int(a[a.index("--seed") + 1])
os.makedirs(out)
if seed == 99:
    print("swlio-sim: cannot draw this world", file=sys.stderr)
    sys.exit(2)
variant = "--disturb" in a or a[a.index("--scenario") + 1] == "field"
ape = 0.01 * seed * ((1.1 if seed % 2 else 1.5) if variant else 1.0)
open(os.path.join(out, "ape.txt"), "w").write(repr(ape))
open(os.path.join(out, "groundtruth.tum"), "w").write("100.0 0 0 0 0 0 0 1\\n")
"""

# swlio-run stand-in: logs its arguments; its trajectory file holds the recording's APE.
FAKE_RUN = """\
#!/usr/bin/python3
import json, os, sys
a = sys.argv[1:]
with open(os.environ["FAKE_LOG"], "a") as f:
    f.write(json.dumps(["run"] + a) + "\\n")
rec, out = a[0], a[a.index("--out") + 1]
open(out, "w").write(open(os.path.join(rec, "ape.txt")).read())
"""


class ApeRealizations(StandInTest):
    SCRIPT = SCRIPT
    PROGRAMS = {"swlio-sim": FAKE_SIM, "swlio-run": FAKE_RUN, "swlio-eval": FAKE_EVAL}
    evaluate = StandInTest.run_script

    def calls(self, kind):
        return [c[1:] for c in self.logged() if c[0] == kind]

    def test_pairs_against_a_second_scenario(self):
        r = self.evaluate("--scenario", "loop943", "--world-seed", "2", "--seeds", "3,4,5",
                          "--against", "field", "--", "--wheel", "on")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| seed | base APE (m) | field APE (m) | ratio |", r.stdout)
        self.assertIn("| 3 | 0.0300 | 0.0330 | 1.10 |", r.stdout)
        self.assertIn("| 4 | 0.0400 | 0.0600 | **1.50** |", r.stdout)
        # Ratios 1.10, 1.50, 1.10; sums 0.12 against 0.148.
        self.assertIn("ratio: median 1.10, of the sums 1.23, largest 1.50; 1 of 3 over 1.25",
                      r.stdout)
        sims = self.calls("sim")
        self.assertEqual(len(sims), 6)
        for a in sims:
            self.assertEqual(a[a.index("--world-seed") + 1], "2")
        scenarios = sorted(a[a.index("--scenario") + 1] for a in sims)
        self.assertEqual(scenarios, ["field"] * 3 + ["loop943"] * 3)
        runs = self.calls("run")
        self.assertEqual(len(runs), 6)
        for a in runs:
            self.assertEqual(a[a.index("--loop-closure") + 1], "off")
            self.assertEqual(a[-2:], ["--wheel", "on"])

    def test_disturbances_on_the_same_scenario_and_recordings_kept(self):
        args = ("--scenario", "aggressive", "--world-seed", "42", "--seeds", "1",
                "--disturb", "vibration", "--bound", "1.05")
        r = self.evaluate(*args)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| 1 | 0.0100 | 0.0110 | **1.10** |", r.stdout)
        self.assertIn("1 of 1 over 1.05", r.stdout)
        variant = [a for a in self.calls("sim") if "--disturb" in a]
        self.assertEqual(len(variant), 1)
        self.assertEqual(variant[0][variant[0].index("--scenario") + 1], "aggressive")
        self.assertEqual(variant[0][variant[0].index("--disturb") + 1], "vibration")
        again = self.evaluate(*args)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertEqual(len(self.calls("sim")), 2)  # made once
        self.assertEqual(len(self.calls("run")), 4)  # run each time

    def test_variant_simulator_arguments_go_to_the_variant_alone(self):
        plain = ("--scenario", "aggressive", "--world-seed", "1", "--seeds", "2",
                 "--disturb", "vibration")
        self.assertEqual(self.evaluate(*plain).returncode, 0)
        r = self.evaluate(*plain, "--variant-sim-args", "--vibration-rms 0.01:0.02")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| seed | base APE (m) | vibration --vibration-rms 0.01:0.02 APE (m) |",
                      r.stdout)
        sims = self.calls("sim")
        self.assertEqual(len(sims), 3)  # the base made once, each variant once
        self.assertNotIn("--vibration-rms", sims[0] + sims[1])
        self.assertEqual(sims[2][-2:], ["--vibration-rms", "0.01:0.02"])
        self.assertTrue((self.work / "aggressive_vibration_w1_s2").is_dir())
        self.assertTrue(
            (self.work / "aggressive_vibration_vibration_rms_0.01_0.02_w1_s2").is_dir())
        bad = self.evaluate(*plain, "--variant-sim-args", "--vibration-rms '0.01")
        self.assertEqual(bad.returncode, 2)
        self.assertIn("--variant-sim-args", bad.stderr)

    def test_a_failing_simulation_is_a_clear_error(self):
        r = self.evaluate("--scenario", "loop943", "--world-seed", "2", "--seeds", "99",
                          "--against", "field")
        self.assertEqual(r.returncode, 1)
        self.assertIn("exited with 2", r.stderr)
        self.assertIn("cannot draw this world", r.stderr)
        self.assertNotIn("Traceback", r.stderr)
        self.assertEqual(list(self.work.glob("*_s99")), [])  # no half-made recording kept

    def test_the_arguments_are_checked(self):
        both = self.evaluate("--scenario", "loop943", "--world-seed", "2", "--seeds", "1",
                             "--against", "field", "--disturb", "rain")
        self.assertEqual(both.returncode, 2)
        self.assertIn("not allowed with argument", both.stderr)
        seeds = self.evaluate("--scenario", "loop943", "--world-seed", "2", "--seeds", "1,x",
                              "--against", "field")
        self.assertEqual(seeds.returncode, 2)
        self.assertIn("--seeds takes integers", seeds.stderr)


if __name__ == "__main__":
    unittest.main()
