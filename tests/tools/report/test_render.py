"""End to end: a simulated recording (swlio-sim, 8 s of the `short` drive), an incident built
from it (the recording's files, its lidar.pcap without 2 s of packets, plus the black-box files
of synthetic.py) and a log directory (synthetic.py), each through swlio-report (with the
swlio-run replay for the first two), then rendered in headless Chromium: it renders (a
screenshot that is not blank), the SVG plots are in the DOM, no console errors, nothing loaded
from the network.

SWLIO_BIN_DIR: where swlio-sim, swlio-run and swlio-report are (build/bin). SWLIO_REPORT_KEEP=DIR
keeps the pages and screenshots there.
"""
import math
import os
import re
import shutil
import struct
import subprocess
import tempfile
import time
import unittest

import synthetic

BIN = os.environ.get("SWLIO_BIN_DIR", os.path.join(os.path.dirname(__file__), "../../../build/bin"))
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DURATION_S = 8
GAP = (4, 2)  # health rows 4 and 5 see no LiDAR datagram: none in (103, 105] s host time
REMOTE = re.compile(r"https?://|<script|<link|<img|<iframe|\bsrc=|url\(", re.I)
# Chromium logs every console message as "INFO:CONSOLE:<line>] ..." (or "CONSOLE(<line>)" in
# older versions), errors without their level: the pages have no scripts, so any console line
# is an error here.
CONSOLE_ERROR = re.compile(r"Uncaught|:CONSOLE\b|ERROR:CONSOLE", re.I)


def chromium(*args, timeout=60):
    # A profile of its own per run (2 MB), removed afterwards: it was left in /tmp each time.
    profile_dir = tempfile.TemporaryDirectory(prefix="swlio-chromium-", ignore_cleanup_errors=True)
    with profile_dir as profile:
        cmd = [
            CHROMIUM,
            "--headless",
            "--disable-gpu",
            "--no-sandbox",
            "--no-first-run",
            "--disable-extensions",
            "--user-data-dir=" + profile,
        ]
        return subprocess.run(
            cmd + list(args), capture_output=True, text=True, errors="replace", timeout=timeout
        )


def png_is_not_blank(path):
    """Share of pixels that are not the page's background (near-white)."""
    import matplotlib.image

    img = matplotlib.image.imread(path)[..., :3]
    dark = (img.sum(axis=2) < 2.7).mean()
    return dark


SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../..")


def odometry_from_truth(rows):
    """Ground truth (world frame) moved to start at the origin heading along x, as the daemon's
    odom frame does; every 20th row (10 Hz)."""
    first = [float(v) for v in rows[0].split()]
    qx, qy, qz, qw = first[4:8]
    yaw = math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
    c, s = math.cos(-yaw), math.sin(-yaw)
    out = []
    for row in rows[::20]:
        v = [float(x) for x in row.split()]
        dx, dy, dz = v[1] - first[1], v[2] - first[2], v[3] - first[3]
        out.append(f"{v[0]:.6f} {c * dx - s * dy:.4f} {s * dx + c * dy:.4f} {dz:.4f} 0 0 0 1\n")
    return out


def copy_pcap_without(src, dst, start_s, end_s):
    """lidar.pcap without the packets received in (start_s, end_s]: a LiDAR outage."""
    with open(src, "rb") as f, open(dst, "wb") as out:
        head = f.read(24)
        unit = 1e-9 if head[:4] == b"\x4d\x3c\xb2\xa1" else 1e-6  # nanosecond or microsecond pcap
        out.write(head)
        while len(header := f.read(16)) == 16:
            sec, frac, incl, _ = struct.unpack("<IIII", header)
            data = f.read(incl)
            if not start_s < sec + frac * unit <= end_s:
                out.write(header + data)


def write_incident_from(recording, folder):
    """The recording's files (symlinked; lidar.pcap copied without the outage's packets) plus
    health.csv etc. on its host times (from 100 s), the repository's config/swlio.yaml as
    config.yaml, the daemon's odometry from the simulator's ground truth."""
    os.makedirs(folder)
    for name in os.listdir(recording):
        if name not in ("groundtruth.tum", "lidar.pcap"):
            os.symlink(os.path.join(recording, name), os.path.join(folder, name))
    copy_pcap_without(
        os.path.join(recording, "lidar.pcap"),
        os.path.join(folder, "lidar.pcap"),
        100.0 + GAP[0] - 1,
        100.0 + GAP[0] - 1 + GAP[1],
    )
    synthetic.write_incident(folder, t0_s=100.0, rows=DURATION_S + 1, gap=GAP)
    with open(os.path.join(recording, "groundtruth.tum")) as f:
        rows = [line for line in f if line.strip() and not line.startswith("#")]
    with open(os.path.join(folder, "odometry.tum"), "w") as f:
        f.writelines(odometry_from_truth(rows))
    os.remove(os.path.join(folder, "config.yaml"))
    shutil.copy(os.path.join(SOURCE, "config/swlio.yaml"), os.path.join(folder, "config.yaml"))


@unittest.skipIf(
    CHROMIUM is None,
    "chromium is not installed (Debian package chromium; " "scripts/install-deps installs it)",
)
class Render(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        for tool in ("swlio-sim", "swlio-run", "swlio-report"):
            if not os.access(os.path.join(BIN, tool), os.X_OK):
                raise unittest.SkipTest(f"no swlio-sim/swlio-run/swlio-report in {BIN}: build them")
        cls._tmp = tempfile.TemporaryDirectory(prefix="swlio-report-render-")
        cls.dir = cls._tmp.name
        rec = os.path.join(cls.dir, "rec")
        subprocess.run(
            [
                os.path.join(BIN, "swlio-sim"),
                "--scenario",
                "short",
                "--seed",
                "1",
                "--duration",
                str(DURATION_S),
                "--out",
                rec,
            ],
            check=True,
            capture_output=True,
        )
        write_incident_from(rec, os.path.join(cls.dir, "incident"))
        synthetic.write_logdir(os.path.join(cls.dir, "logdir"))
        cls.pages, cls.seconds = {}, {}
        for name in ("rec", "incident", "logdir"):
            start = time.monotonic()
            out = os.path.join(cls.dir, name + ".html")
            done = subprocess.run(
                [os.path.join(BIN, "swlio-report"), os.path.join(cls.dir, name), "-o", out],
                capture_output=True,
                text=True,
            )
            cls.seconds[name] = time.monotonic() - start
            assert done.returncode == 0, done.stderr
            cls.pages[name] = out

    @classmethod
    def tearDownClass(cls):
        keep = os.environ.get("SWLIO_REPORT_KEEP")
        if keep:
            os.makedirs(keep, exist_ok=True)
            for name in os.listdir(cls.dir):
                if name.endswith((".html", ".png")):
                    shutil.copy(os.path.join(cls.dir, name), keep)
        cls._tmp.cleanup()

    def check_page(self, name, min_svgs):
        page = self.pages[name]
        with open(page, encoding="utf-8") as f:
            html = f.read()
        self.assertIsNone(REMOTE.search(html), "an external reference in the page")
        shot = os.path.join(self.dir, name + ".png")
        chromium("--screenshot=" + shot, "--window-size=1280,2400", "file://" + page)
        self.assertTrue(os.path.isfile(shot), "no screenshot")
        self.assertGreater(png_is_not_blank(shot), 0.02, "the screenshot is blank")
        dom = chromium("--enable-logging=stderr", "--v=0", "--dump-dom", "file://" + page)
        self.assertGreaterEqual(dom.stdout.count("<svg"), min_svgs)
        self.assertIn("Verdict per subsystem", dom.stdout)
        bad = [line for line in dom.stderr.splitlines() if CONSOLE_ERROR.search(line)]
        self.assertEqual(bad, [], "console errors")
        print(
            f"{name}: {os.path.getsize(page) / 1024:.0f} KB, built in {self.seconds[name]:.1f} s, "
            f"{dom.stdout.count('<svg')} SVG plots"
        )
        return dom.stdout

    def test_console_errors_are_seen(self):
        """The console check itself: a page with a failing script is caught."""
        bad = os.path.join(self.dir, "bad.html")
        with open(bad, "w") as f:
            f.write("<html><body><script>undefinedFunction();</script></body></html>")
        dom = chromium("--enable-logging=stderr", "--v=0", "--dump-dom", "file://" + bad)
        self.assertTrue(any(CONSOLE_ERROR.search(line) for line in dom.stderr.splitlines()))

    def test_recording(self):
        dom = self.check_page("rec", min_svgs=5)
        self.assertIn("replay (swlio-run)", dom)
        self.assertIn("a recording folder", dom)

    def test_incident(self):
        dom = self.check_page("incident", min_svgs=12)
        self.assertIn("daemon odometry (odometry.tum)", dom)
        self.assertIn("LiDAR-IMU time offset", dom)  # health.csv's imu_time_offset_ms
        self.assertRegex(
            dom,
            r"LiDAR</td><td><span class=\"badge failed\">failed</span></td>"
            r"<td>LiDAR silent ≥ 2.0 s",
        )
        self.assertIn("lidar: no datagram for 1.0 s", dom)  # the log line near the event
        self.assertNotIn("replayed with defaults", dom)  # the incident's config.yaml was used
        self.assertIn("sweeps (replay) silent 2.", dom)  # the replay saw the outage too

    def test_log_directory(self):
        dom = self.check_page("logdir", min_svgs=6)
        self.assertIn("the daemon's log directory", dom)
        self.assertIn("degraded: CPU: 4 sweeps skipped", dom)


if __name__ == "__main__":
    unittest.main()
