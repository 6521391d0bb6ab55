"""The verdict rules on synthetic incidents: each fault gives its subsystem's level and reason."""
import os
import tempfile
import unittest

import synthetic
from swlio_report import evidence, inputs, timeline, verdicts


def judge(folder):
    inp = inputs.read(folder)
    tl = timeline.build(inp, None)
    ctx = verdicts.Context(inp, evidence.build(inp, tl), tl)
    return {v.subsystem: v for v in verdicts.judge(ctx)}


class Verdicts(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="swlio-report-test-")
        self.dir = os.path.join(self._tmp.name, "inc")

    def tearDown(self):
        self._tmp.cleanup()

    def test_lidar_gap_fails_the_lidar_with_its_length(self):
        synthetic.write_incident(self.dir, gap=(20, 3))
        v = judge(self.dir)
        self.assertEqual(v["LiDAR"].label(), "failed")
        self.assertIn("LiDAR silent ≥ 3.0 s from 14:32:19.0", v["LiDAR"].reason())
        self.assertIn("incident: lidar_silent at 14:32:21.0", v["LiDAR"].reason())
        self.assertEqual(v["IMU"].label(), "ok")
        self.assertEqual(v["clocks"].label(), "ok")
        self.assertEqual(v["estimator"].label(), "degraded")  # tracking state degraded meanwhile
        self.assertEqual(v["black box"].label(), "ok")

    def test_clean_span_is_ok_everywhere(self):
        synthetic.write_incident(self.dir, gap=None)
        for name, v in judge(self.dir).items():
            self.assertEqual(v.label(), "ok", f"{name}: {v.reason()}")

    def test_a_gap_shorter_than_a_row_is_not_a_silence(self):
        synthetic.write_incident(self.dir, gap=(20, 0))
        self.assertNotIn("LiDAR silent", judge(self.dir)["LiDAR"].reason())

    def test_checksum_errors_degrade_the_imu(self):
        synthetic.write_incident(self.dir, gap=None, checksum_at=12)
        v = judge(self.dir)["IMU"]
        self.assertEqual(v.label(), "degraded")
        self.assertIn("1 checksum errors", v.reason())

    def test_a_reinitialization_fails_the_estimator(self):
        synthetic.write_incident(self.dir, gap=None, reinit_at=30)
        v = judge(self.dir)["estimator"]
        self.assertEqual(v.label(), "failed")
        self.assertIn("1 re-initialization(s), first at 14:32:30.0", v.reason())

    def test_an_operators_reset_is_said_and_fails_nothing(self):
        synthetic.write_incident(self.dir, gap=None, reset_at=25)
        v = judge(self.dir)["estimator"]
        self.assertEqual(v.label(), "ok")
        self.assertIn("no re-initialization", v.reason())
        self.assertIn("1 operator reset(s), first at 14:32:25.0", v.reason())

    def test_a_divergence_beside_an_operators_reset_still_fails(self):
        synthetic.write_incident(self.dir, gap=None, reset_at=25, reinit_at=30)
        v = judge(self.dir)["estimator"]
        self.assertEqual(v.label(), "failed")
        self.assertIn("1 re-initialization(s), first at 14:32:30.0", v.reason())

    def test_missing_black_box_file_degrades_the_black_box(self):
        synthetic.write_incident(self.dir, gap=None)
        os.remove(os.path.join(self.dir, "log.txt"))
        v = judge(self.dir)["black box"]
        self.assertEqual(v.label(), "degraded")
        self.assertIn("absent: log.txt", v.reason())

    def test_log_directory_from_status_lines(self):
        os.makedirs(self.dir)
        with open(os.path.join(self.dir, "swliod.log"), "w") as f:
            f.write(synthetic.log_text(gap=None).replace("reinit 0", "reinit 2"))
        v = judge(self.dir)
        self.assertEqual(v["estimator"].label(), "failed")
        self.assertEqual(v["black box"].label(), "no data")

    def test_status_lines_subtract_the_operators_resets(self):
        os.makedirs(self.dir)
        text = synthetic.log_text(gap=None)
        with open(os.path.join(self.dir, "swliod.log"), "w") as f:
            f.write(text.replace("reinit 0 (operator resets 0)", "reinit 1 (operator resets 1)"))
        self.assertEqual(judge(self.dir)["estimator"].label(), "ok")
        with open(os.path.join(self.dir, "swliod.log"), "w") as f:
            f.write(text.replace("reinit 0 (operator resets 0)", "reinit 2 (operator resets 1)"))
        self.assertEqual(judge(self.dir)["estimator"].label(), "failed")

    def test_log_directory_warnings(self):
        v = judge(synthetic.write_logdir(self.dir))
        self.assertEqual(v["clocks"].label(), "degraded")
        self.assertIn("1 lidar clock jumps, first at 14:35:30.0", v["clocks"].reason())
        self.assertEqual(v["CPU / queues"].label(), "degraded")
        self.assertIn("4 sweeps skipped behind; 12 queue drops", v["CPU / queues"].reason())
        self.assertEqual(v["LiDAR"].label(), "ok")

    def test_status_lines_zero_rate_only_after_streaming_fails(self):
        os.makedirs(self.dir)
        lines = synthetic.log_text(gap=None).splitlines(True)
        status = [i for i, line in enumerate(lines) if " status " in line]
        for i in status[:2] + status[-2:]:  # waiting for the sensors, then silent at the end
            lines[i] = lines[i].replace("10.0 sweeps/s", "0.0 sweeps/s")
        with open(os.path.join(self.dir, "swliod.log"), "w") as f:
            f.writelines(lines)
        v = judge(self.dir)["LiDAR"]
        self.assertEqual(v.label(), "failed")
        self.assertIn("0 sweeps/s in 2 status line(s) from 14:32:30.0", v.reason())

    def test_a_recorded_wall_clock_step_degrades_the_clocks(self):
        os.makedirs(self.dir)
        with open(os.path.join(self.dir, "manifest.yaml"), "w") as f:
            f.write("format_version: 2\nrealtime_minus_monotonic_ns: 1796399846839300466\n")
        with open(os.path.join(self.dir, "clock_offsets.csv"), "w") as f:
            f.write("t_monotonic_ns,realtime_minus_monotonic_ns\n")
            f.write("100000000000,1796399846839300466\n130000000000,1796399847339300466\n")
        v = judge(self.dir)["clocks"]
        self.assertEqual(v.label(), "degraded")
        self.assertIn("wall clock stepped 1 time(s), by +500.0 ms at", v.reason())


if __name__ == "__main__":
    unittest.main()
