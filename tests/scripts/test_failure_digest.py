"""scripts/failure-digest on a LastTest.log in CTest's format: a passed test is left out, a
failed GoogleTest test shows its assertions and notes (not its log lines), a crashed test its
last lines, and a long failure is cut at the limit."""
import subprocess
import tempfile
import unittest
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "failure-digest"


def section(index, name, output, passed):
    return "\n".join([
        "----------------------------------------------------------",
        f"{index}/3 Testing: {name}", f"{index}/3 Test: {name}", f'Command: "bin" "{name}"',
        "Directory: /b/tests", f'"{name}" start time: Dec 05 12:00 UTC', "Output:",
        "----------------------------------------------------------", *output,
        "<end of output>", "Test time =   1.00 sec",
        "----------------------------------------------------------",
        "Test Passed." if passed else "Test Failed.", ""])


class FailureDigest(unittest.TestCase):
    def digest(self, log, *args):
        with tempfile.TemporaryDirectory() as d:
            (Path(d) / "Testing" / "Temporary").mkdir(parents=True)
            (Path(d) / "Testing" / "Temporary" / "LastTest.log").write_text(log)
            r = subprocess.run([str(SCRIPT), d, *args], capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            return r.stdout

    def test_failed_assertions_notes_and_crashes(self):
        log = section(1, "a.Passes", ["[ RUN      ] A.Passes", "fine"], True) + section(
            2, "b.Fails", ["[ RUN      ] B.Fails", "[info] a log line",
                           "/src/b_test.cpp:12: Failure", "Expected equality of these values:",
                           "  reasons", "    Which is: { \"clock_jump\" }",
                           "[ note ] the simulator sent up to 353 ms late",
                           "[  FAILED  ] B.Fails (45000 ms)"], False) + section(
            3, "c.Crashes", ["starting", "half way"], False)
        out = self.digest(log)
        self.assertIn("2 test(s)", out)
        self.assertNotIn("a.Passes", out)
        self.assertIn("-- b.Fails\n   /src/b_test.cpp:12: Failure\n", out)
        self.assertIn("Which is: { \"clock_jump\" }", out)
        self.assertIn("[ note ] the simulator sent up to 353 ms late", out)
        self.assertNotIn("a log line", out)
        self.assertIn("-- c.Crashes\n   starting\n   half way\n", out)

    def test_nothing_failed_prints_nothing_and_long_failures_are_cut(self):
        self.assertEqual(self.digest(section(1, "a.Passes", ["ok"], True)), "")
        many = ["/src/x.cpp:1: Failure"] + [f"line {i}" for i in range(100)]
        out = self.digest(section(1, "x.Fails", many, False), "--lines", "10")
        self.assertIn("line 7\n", out)
        self.assertNotIn("line 9\n", out)
        self.assertIn("(92 more lines in LastTest.log)", out)


if __name__ == "__main__":
    unittest.main()
