"""Stand-ins for swlio's programs, shared by the scripts' tests: each a small Python program
written into a bin folder that SWLIO_BIN_DIR then points at."""
import stat
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
