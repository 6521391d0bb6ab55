"""Truncated and garbage inputs: the page is still written, says what was wrong, never a
traceback (fixed seeds)."""
import os
import random
import shutil
import subprocess
import sys
import tempfile
import unittest

import synthetic
from swlio_report import inputs, main

FILES = ("health.csv", "log.txt", "odometry.tum", "incident.yaml", "config.yaml")
REPORT = os.path.join(os.path.dirname(main.__file__), "..", "swlio-report")


def page_of(folder):
    return main.build_page(inputs.read(folder), None)


class Malformed(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="swlio-report-test-")
        self.good = synthetic.write_incident(os.path.join(self._tmp.name, "good"))
        self.dir = os.path.join(self._tmp.name, "bad")

    def tearDown(self):
        self._tmp.cleanup()

    def fresh(self):
        shutil.rmtree(self.dir, ignore_errors=True)
        shutil.copytree(self.good, self.dir)

    def mutate(self, name, change):
        path = os.path.join(self.dir, name)
        with open(path, "rb") as f:
            data = f.read()
        with open(path, "wb") as f:
            f.write(change(data))

    def test_truncated_anywhere(self):
        rng = random.Random(35)
        for name in FILES:
            for _ in range(8):
                self.fresh()
                self.mutate(name, lambda d: d[: rng.randrange(len(d) + 1)])
                html = page_of(self.dir)
                self.assertIn("Verdict per subsystem", html, name)

    def test_garbage_bytes_anywhere(self):
        rng = random.Random(36)
        for name in FILES:
            for _ in range(8):
                self.fresh()

                def scramble(d):
                    b = bytearray(d)
                    for _ in range(1 + len(b) // 50):
                        b[rng.randrange(len(b))] = rng.randrange(256)
                    return bytes(b)

                self.mutate(name, scramble)
                html = page_of(self.dir)
                self.assertIn("Notes on the input", html, name)

    def test_truncated_health_csv_is_noted(self):
        self.fresh()
        self.mutate("health.csv", lambda d: d[:-40])
        html = page_of(self.dir)
        self.assertIn("health.csv: 1 malformed line(s) skipped (line 41)", html)

    def test_garbage_files_and_empty_files(self):
        self.fresh()
        self.mutate("incident.yaml", lambda d: b"{{{: [\x00\xff")
        self.mutate("health.csv", lambda d: b"")
        self.mutate("log.txt", lambda d: bytes(range(256)) * 20)
        html = page_of(self.dir)
        self.assertIn("incident.yaml: not YAML", html)
        self.assertIn("health.csv: empty", html)
        self.assertIn("line(s) that are not log lines skipped", html)

    def test_non_finite_numbers_are_not_drawn(self):
        self.fresh()
        self.mutate("odometry.tum", lambda d: d + b"200.0 nan 1 0 0 0 0 1\n300.0 inf 1 0 0 0 0 1\n")
        html = page_of(self.dir)
        self.assertIn("odometry.tum: 2 malformed line(s) skipped", html)
        self.assertNotIn("nan", html.split("<svg", 1)[1].lower().split("notes on the input")[0])

    def test_only_some_files(self):
        for keep in FILES:
            self.fresh()
            for name in FILES:
                if name != keep:
                    os.remove(os.path.join(self.dir, name))
            html = page_of(self.dir)
            self.assertIn("Verdict per subsystem", html, keep)

    def test_not_an_input(self):
        empty = os.path.join(self._tmp.name, "empty")
        os.makedirs(empty)
        for path in (empty, os.path.join(self.good, "health.csv"), "/nonexistent/swlio"):
            done = subprocess.run(
                [sys.executable, REPORT, path, "-o", os.devnull], capture_output=True, text=True
            )
            self.assertEqual(done.returncode, 2, path)
            self.assertIn("swlio-report:", done.stderr)
            self.assertNotIn("Traceback", done.stderr)

    def test_unwritable_output(self):
        done = subprocess.run(
            [sys.executable, REPORT, self.good, "-o", "/nonexistent/dir/page.html"],
            capture_output=True,
            text=True,
        )
        self.assertEqual(done.returncode, 1)
        self.assertIn("swlio-report: cannot write /nonexistent/dir/page.html", done.stderr)


class InstalledLayout(unittest.TestCase):
    def test_script_finds_its_package_under_share(self):
        """<prefix>/bin/swlio-report with <prefix>/share/swlio/report/swlio_report (the install
        and build/bin layouts)."""
        with tempfile.TemporaryDirectory() as prefix:
            os.makedirs(os.path.join(prefix, "bin"))
            shutil.copy(REPORT, os.path.join(prefix, "bin", "swlio-report"))
            shutil.copytree(
                os.path.dirname(main.__file__),
                os.path.join(prefix, "share", "swlio", "report", "swlio_report"),
            )
            incident = synthetic.write_incident(os.path.join(prefix, "inc"))
            out = os.path.join(prefix, "page.html")
            done = subprocess.run(
                [os.path.join(prefix, "bin", "swlio-report"), incident, "-o", out],
                capture_output=True,
                text=True,
                env={"PATH": "/usr/bin:/bin"},
            )
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertTrue(os.path.getsize(out) > 10000)


if __name__ == "__main__":
    unittest.main()
