"""scripts/time-offset-eval against stand-ins for swlio-sim, swlio-run and swlio-eval: every case
runs --draws draws estimated and with the offset known (set + clock chain, --time-offset fixed),
each with its own floor; the table gives both medians with their ranges and the ratio of the
medians, bold over 1.10, the offset applied at 32 s from draw 0's diagnostics; the runs with the
offset known are made once per work folder; a failing run is a clear error with exit status 1."""
import json
import re
import unittest
from pathlib import Path

from stand_ins import FAKE_EVAL, StandInTest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "time-offset-eval"

# swlio-sim stand-in: a recording folder with a ground truth starting at 100 s, an IMU
# receive-time file for scripts/shift-imu-rx and its own arguments (sim_args.json).
FAKE_SIM = """\
#!/usr/bin/python3
import json, os, sys
a = sys.argv[1:]
out = a[a.index("--out") + 1]
os.makedirs(out)
open(os.path.join(out, "sim_args.json"), "w").write(json.dumps(a))
gt = "# t x y z qx qy qz qw\\n100.0 0 0 0 0 0 0 1\\n"
open(os.path.join(out, "groundtruth.tum"), "w").write(gt)
open(os.path.join(out, "imu.rx.csv"), "w").write("t_rx_ns\\n100000000000\\n")
"""

# swlio-run stand-in: logs its arguments; its trajectory file holds the APE swlio-eval will
# print: 0.02 with the offset known, 0.024 estimated on seed 42's recordings, 0.02 on seed 1's,
# times 1 + 1000 * (floor/0.01 - 1). Its diagnostics apply the recording's offset (from the
# folder's name) from 32 s into the drive on. A recording holding a file "broken" fails.
FAKE_RUN = """\
#!/usr/bin/python3
import json, os, re, sys
a = sys.argv[1:]
rec, out, floor = a[0], a[a.index("--out") + 1], float(a[a.index("--lidar-floor-m") + 1])
with open(os.environ["FAKE_LOG"], "a") as f:
    f.write(json.dumps(a) + "\\n")
name = os.path.basename(rec)
if os.path.exists(os.path.join(rec, "broken")):
    print("swlio-run: the recording is broken", file=sys.stderr)
    sys.exit(3)
known = "--time-offset" in a
base = 0.02 if known or "_1_" in name else 0.024
open(out, "w").write(repr(base * (1 + 1000 * (floor / 0.01 - 1))))
if "--diagnostics" in a:
    offset_ms = float(re.search(r"_(?:o|rx)(-?[0-9.]+)$", name).group(1))
    with open(a[a.index("--diagnostics") + 1], "w") as f:
        f.write("t_ns,time_offset_ms\\n100000000000,0.0\\n131900000000,0.0\\n"
                "132000000000,%g\\n" % offset_ms)
"""


class TimeOffsetEval(StandInTest):
    SCRIPT = SCRIPT
    PROGRAMS = {"swlio-sim": FAKE_SIM, "swlio-run": FAKE_RUN, "swlio-eval": FAKE_EVAL}
    evaluate = StandInTest.run_script
    runs = StandInTest.logged

    def test_medians_of_the_draws_and_their_ratio(self):
        r = self.evaluate("--seeds", "42,1", "--offsets", "10,-5")
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = [line for line in r.stdout.splitlines() if line.startswith("| `aggressive`")]
        self.assertEqual(len(rows), 6)  # two seeds and the shifted recording, two offsets each
        # Draw k's floor is 0.01 (1 + k 1e-5): the stand-in's APE is base (1 + k 0.01).
        self.assertIn("| `aggressive` 42 | +10 | 10.00 | 0.0242 (0.0240–0.0245) | "
                      "0.0202 (0.0200–0.0204) | **1.20** |", rows)
        self.assertIn("| `aggressive` 1 | -5 | -5.00 | 0.0202 (0.0200–0.0204) | "
                      "0.0202 (0.0200–0.0204) | 1.00 |", rows)
        self.assertIn("| `aggressive` 42, IMU receive times shifted | -5 | -5.00 |", r.stdout)
        self.assertIn("medians of 3 draws; over 1.10: 4 of 6; mean ratio 1.133, worst 1.20",
                      r.stdout)
        runs = self.runs()
        known = [x for x in runs if "--time-offset" in x]
        est = [x for x in runs if "--time-offset" not in x]
        self.assertEqual((len(known), len(est)), (18, 18))
        for x in known:
            self.assertEqual(x[x.index("--time-offset") + 1], "fixed")
            set_ms = float(re.search(r"_(?:o|rx)(-?[0-9.]+)$", x[0]).group(1))
            self.assertEqual(x[x.index("--time-offset-init-ms") + 1], f"{set_ms - 0.25:.4f}")
        for x in runs:
            self.assertEqual(x[x.index("--loop-closure") + 1], "off")
        # Only draw 0 of the estimated runs writes diagnostics: one per case.
        self.assertEqual(sum("--diagnostics" in x for x in est), 6)
        floors = sorted({float(x[x.index("--lidar-floor-m") + 1]) for x in runs})
        self.assertEqual(len(floors), 3)
        self.assertEqual(floors[0], 0.01)

    def test_realizations_of_one_world_and_the_median_per_offset(self):
        r = self.evaluate("--seeds", "1,12", "--world-seed", "7", "--offsets=-10,5",
                          "--shifted-seed", "", "--draws", "1")
        self.assertEqual(r.returncode, 0, r.stderr)
        for seed in (1, 12):
            for offset in ("-10", "5"):
                rec = self.work / f"aggressive_{seed}_w7_o{offset}"
                args = json.loads((rec / "sim_args.json").read_text())
                self.assertEqual(args[args.index("--world-seed") + 1], "7")
                self.assertEqual(args[args.index("--seed") + 1], str(seed))
                self.assertEqual(args[args.index("--time-offset-ms") + 1], offset + ".0")
        self.assertIn("| `aggressive` 1 (world 7) | -10 |", r.stdout)
        self.assertIn("| `aggressive` 12 (world 7) | +5 |", r.stdout)
        # Seed 1's estimate is as good as the offset known (1.00), seed 12's 1.20×.
        self.assertIn("| -10 | 2 | 1.10 | 1 |", r.stdout)
        self.assertIn("| +5 | 2 | 1.10 | 1 |", r.stdout)

    def test_the_runs_with_the_offset_known_are_made_once(self):
        self.assertEqual(self.evaluate("--seeds", "1", "--offsets", "5", "--shifted-seed", "",
                                       "--draws", "2").returncode, 0)
        self.log.unlink()
        r = self.evaluate("--seeds", "1", "--offsets", "5", "--shifted-seed", "", "--draws", "2",
                          "--tag", "other", "--config", "some.yaml")
        self.assertEqual(r.returncode, 0, r.stderr)
        runs = self.runs()
        self.assertEqual(len(runs), 2)
        for x in runs:
            self.assertNotIn("--time-offset", x)
            self.assertEqual(x[x.index("--config") + 1], "some.yaml")
            self.assertIn(".other.d", x[x.index("--out") + 1])
        self.assertIn("medians of 2 draws; over 1.10: 0 of 1", r.stdout)

    def test_a_failing_run_is_a_clear_error(self):
        broken = self.work / "aggressive_1_o5"
        broken.mkdir(parents=True)  # an existing recording is used as it is
        (broken / "groundtruth.tum").write_text("100.0 0 0 0 0 0 0 1\n")
        (broken / "broken").write_text("")
        r = self.evaluate("--seeds", "1", "--offsets", "5", "--shifted-seed", "", "--draws", "1")
        self.assertEqual(r.returncode, 1)
        self.assertIn("exited with 3", r.stderr)
        self.assertIn("the recording is broken", r.stderr)
        self.assertNotIn("Traceback", r.stderr)

    def test_draws_must_be_positive(self):
        r = self.evaluate("--draws", "0")
        self.assertEqual(r.returncode, 2)
        self.assertIn("--draws and --jobs must be at least 1", r.stderr)


if __name__ == "__main__":
    unittest.main()
