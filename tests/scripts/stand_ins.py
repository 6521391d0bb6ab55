"""Stand-ins for swlio's programs, shared by the scripts' tests: each a small Python program
written into a bin folder that SWLIO_BIN_DIR then points at."""
import json
import os
import stat
import subprocess
import tempfile
import unittest
from pathlib import Path

# swlio-eval stand-in: the trajectory file holds the APE RMSE to print.
FAKE_EVAL = """\
#!/usr/bin/python3
import json, sys
assert "--json" in sys.argv and sys.argv[4:6] == ["--format", "tum"], sys.argv
print(json.dumps({"n": 100, "rmse": float(open(sys.argv[3]).read())}))
"""


def write_bin(folder, programs):
    """Writes {name: text} as executables into `folder` (made if missing)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in programs.items():
        p = folder / name
        p.write_text(text)
        p.chmod(p.stat().st_mode | stat.S_IXUSR)


class StandInTest(unittest.TestCase):
    """A script's test against stand-ins: SCRIPT run with --work in a temporary folder, the
    PROGRAMS ({name: text}) in its bin folder as SWLIO_BIN_DIR, each logging to FAKE_LOG."""
    SCRIPT = None
    PROGRAMS = {}

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        d = Path(self.tmp.name)
        write_bin(d / "bin", self.PROGRAMS)
        self.log = d / "runs.jsonl"
        self.work = d / "work"
        self.env = dict(os.environ, SWLIO_BIN_DIR=str(d / "bin"), FAKE_LOG=str(self.log))

    def tearDown(self):
        self.tmp.cleanup()

    def run_script(self, *args):
        return subprocess.run([str(self.SCRIPT), "--work", str(self.work), *args],
                              capture_output=True, text=True, env=self.env)

    def logged(self):
        """Every logged call's arguments, in order."""
        if not self.log.exists():
            return []
        return [json.loads(line) for line in self.log.read_text().splitlines()]
