"""swlio-report's readers: health.csv, log and status lines, incident.yaml, PCD, TUM."""
import os
import struct
import tempfile
import unittest

import synthetic
from swlio_report import incident, inputs, logs, pointcloud, series, tables


class TempDir(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="swlio-report-test-")
        self.dir = self._tmp.name

    def tearDown(self):
        self._tmp.cleanup()

    def write(self, name, text, mode="w"):
        path = os.path.join(self.dir, name)
        with open(path, mode) as f:
            f.write(text)
        return path


class HealthCsv(TempDir):
    def test_columns_numbers_and_strings(self):
        notes = []
        table = tables.read_csv(self.write("health.csv", synthetic.health_rows(rows=10)), notes)
        self.assertEqual(notes, [])
        self.assertEqual(table.rows, 10)
        self.assertEqual(table.numbers("t_ns")[0], 100e9)
        self.assertEqual(table.col("estimator_tracking")[0], "tracking")
        self.assertEqual(table.col("utc")[0], "2026-12-04T14:32:00.000Z")
        self.assertEqual(table.numbers("estimator_tracking")[0], None)
        self.assertEqual(table.col("no_such_column"), [None] * 10)

    def test_rates_and_silences_from_counters(self):
        table = tables.read_csv(
            self.write("health.csv", synthetic.health_rows(rows=10, gap=(4, 3))), []
        )
        ts = series.seconds(table.numbers("t_ns"))
        rates = series.rate(ts, table.numbers("lidar_datagrams"))
        self.assertEqual(rates[0], (101.0, 750.0))
        self.assertEqual([r for _, r in rates[3:6]], [0.0, 0.0, 0.0])
        self.assertEqual(series.silences(ts, table.numbers("lidar_datagrams"), 1.0), [(103.0, 3.0)])
        self.assertEqual(series.increase(table.numbers("lidar_datagrams")), 750 * 6)

    def test_counter_restart_counts_from_zero(self):
        self.assertEqual(series.increase([5, 7, 2, 4]), 2 + 2 + 2)


class LogLines(unittest.TestCase):
    def test_line(self):
        line = logs.parse_line("2026-12-04T14:32:07.120+0000 warn  [1234] degraded: CPU: 3 sweeps")
        self.assertEqual(line.level, "warn")
        self.assertEqual(line.tid, 1234)
        self.assertEqual(line.message, "degraded: CPU: 3 sweeps")
        self.assertAlmostEqual(line.utc_s, logs.parse_utc("2026-12-04T14:32:07.120Z"))
        self.assertTrue(line.is_problem())

    def test_time_zone_and_spdlog_level_names(self):
        a = logs.parse_line("2026-12-04T15:32:07.000+0100 warning [1] x")
        b = logs.parse_line("2026-12-04T14:32:07.000Z info [1] x")
        self.assertEqual(a.level, "warn")
        self.assertAlmostEqual(a.utc_s, b.utc_s)

    def test_garbage_is_counted(self):
        notes = []
        text = synthetic.log_text(rows=10) + "\x00\x01garbage\n2026-12-04T14:3"
        lines = logs.parse_lines(text, "log.txt", notes)
        self.assertGreater(len(lines), 2)
        self.assertEqual(notes, ["log.txt: 2 line(s) that are not log lines skipped"])

    def test_status_line(self):
        line = logs.parse_line(synthetic.log_text(rows=5).splitlines()[0])
        fields = logs.parse_status(line.message)
        self.assertEqual(fields["state"], "tracking")
        self.assertEqual(fields["lidar_pkt_hz"], 750)
        self.assertEqual(fields["imu_hz"], 400)
        self.assertEqual(fields["max_update_ms"], 9.5)
        self.assertEqual(fields["imu_clock_jumps"], 0)
        self.assertEqual(fields["lag_pose_ms"], 1.1)
        self.assertEqual(fields["operator_resets"], 0)
        self.assertEqual(logs.parse_status("loop closure: node 3"), {})

    def test_a_real_daemon_log(self):
        """data/swliod-live.log: swliod on a live simulated drive (a 2.5 s LiDAR outage, serial
        garbage), stopped after the drive: spdlog's "+00:00" zone and "warning" level."""
        notes = []
        path = os.path.join(os.path.dirname(__file__), "data", "swliod-live.log")
        with open(path) as f:
            lines = logs.parse_lines(f.read(), "swliod.log", notes)
        self.assertEqual(notes, [])
        self.assertEqual(len(lines), 21)
        self.assertEqual(lines[0].level, "warn")
        self.assertAlmostEqual(lines[0].utc_s, logs.parse_utc("2026-12-04T16:25:56.030Z"))
        status = [logs.parse_status(line.message) for line in lines]
        status = [s for s in status if s]
        self.assertEqual(len(status), 12)
        self.assertTrue(status[-1]["final"])
        # The log is older than the fields added since; every other field is read.
        self.assertEqual(set(logs.STATUS_FIELDS) - set(status[0]), logs.NEWER_STATUS_FIELDS)
        self.assertEqual(status[0]["state"], "initializing")

    def test_rotated_files_oldest_first(self):
        with tempfile.TemporaryDirectory() as d:
            for name in ("swliod.log", "swliod.2.log", "swliod.1.log"):
                open(os.path.join(d, name), "w").close()
            self.assertEqual(
                [os.path.basename(p) for p in logs.log_files(d)],
                ["swliod.2.log", "swliod.1.log", "swliod.log"],
            )


class IncidentYaml(TempDir):
    def test_spec_example(self):
        notes = []
        inc = incident.read(self.write("incident.yaml", synthetic.incident_yaml()), notes)
        self.assertEqual(notes, [])
        self.assertEqual(inc.reason, "lidar_silent")
        self.assertEqual(inc.t_event_ns, 121_000_000_000)
        self.assertEqual(inc.span["start_ns"], 100_000_000_000)
        self.assertFalse(inc.span["cut_short"])
        self.assertEqual(
            [(e.reason, e.detail) for e in inc.events],
            [("lidar_silent", "no LiDAR datagram for 1.0 s")],
        )

    def test_kinds(self):
        synthetic.write_incident(os.path.join(self.dir, "inc"))
        self.assertEqual(inputs.detect_kind(os.path.join(self.dir, "inc"))[0], "incident")
        self.write("swliod.log", "")
        self.assertEqual(inputs.detect_kind(self.dir)[0], "logdir")
        self.assertIsNone(inputs.detect_kind(os.path.join(self.dir, "inc", "health.csv"))[0])


class PointCloud(TempDir):
    def test_binary_pcd_subsampled(self):
        n = 10000
        header = (
            "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
            f"WIDTH {n}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {n}\nDATA binary\n"
        )
        data = b"".join(struct.pack("<fff", i, -i, 1.0) for i in range(n))
        path = self.write("map.pcd", header.encode() + data, "wb")
        notes = []
        points, total = pointcloud.read_xy(path, notes, max_points=100)
        self.assertEqual(total, n)
        self.assertEqual(len(points), 100)
        self.assertEqual(points[1], (100.0, -100.0))
        self.assertEqual(notes, [])

    def test_what_stands_up(self):
        ground = [(x * 0.25, y * 0.25, 0.01 * (x % 3)) for x in range(200) for y in range(200)]
        walls = [
            (20.1, y * 0.5, z * 0.2) for y in range(400) for z in range(10)
        ]  # x = 20 m, 200 m long
        drawn = pointcloud.standing(ground + walls)
        self.assertEqual(len(drawn), 400)
        self.assertTrue(all(x == 20.25 for x, _ in drawn))


if __name__ == "__main__":
    unittest.main()
