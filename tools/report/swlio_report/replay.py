"""The recording replayed through `swlio-run` (tools/run/main.cpp): trajectory, per-sweep
timings, registration diagnostics, covariance, loops and the merged map cloud.

swlio-run is looked for in --swlio-run, beside the swlio-report script, then on PATH.
"""
import json
import os
import re
import shutil
import subprocess
import time

from . import pointcloud
from .tables import read_csv, read_tum


class Replay:
    """What swlio-run wrote; absent parts None. `error` says why there is no replay."""

    def __init__(self):
        self.error = None
        self.command = ""
        self.seconds = 0.0
        self.trajectory = self.timings = self.diagnostics = self.covariance = None
        self.loops = None
        self.map_points = []  # [(x, y)] subsampled
        self.map_total = 0  # points in the PCD
        self.summary = {}  # swlio-run's JSON summary line(s)
        self.stderr_tail = []
        self.notes = []  # problems with the replay (not with the input)
        self.divergences = []  # [(host s, reason)] of the sweeps where the replay re-initialized


def find_swlio_run(explicit, script_dir):
    if explicit:
        return explicit if os.access(explicit, os.X_OK) else None
    beside = os.path.join(script_dir, "swlio-run")
    if os.access(beside, os.X_OK):
        return beside
    return shutil.which("swlio-run")


def _command(program, path, out, config):
    cmd = [
        program,
        path,
        "--out",
        f"{out}/traj.tum",
        "--timings",
        f"{out}/timings.csv",
        "--diagnostics",
        f"{out}/diagnostics.csv",
        "--covariance",
        f"{out}/covariance.csv",
        "--loop-closure",
        "on",
        "--loops",
        f"{out}/loops.csv",
        "--save-map",
        f"{out}/map.swlmap",
        "--map-pcd",
        f"{out}/map.pcd",
    ]
    return cmd + (["--config", config] if config else [])


def _summary(stdout):
    merged = {}
    for line in stdout.splitlines():
        line = line.strip()
        if line.startswith("{"):
            try:
                merged.update(json.loads(line))
            except ValueError:
                pass
    return merged


# tools/run/main.cpp: "swlio-run: sweep ending at 123.4 s: <reason>, re-initializing"
_DIVERGED = re.compile(r"sweep ending at ([\d.]+) s: ([^,\n]+), re-initializing")


def _run(cmd, replay):
    start = time.monotonic()
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, errors="replace")
    except OSError as e:
        replay.error = f"cannot start {cmd[0]}: {e.strerror}"
        return False
    replay.seconds += time.monotonic() - start
    replay.stderr_tail = done.stderr.splitlines()[-8:]
    replay.divergences = [(float(m.group(1)), m.group(2)) for m in _DIVERGED.finditer(done.stderr)]
    if done.returncode != 0:
        replay.error = f"swlio-run exited with {done.returncode}: " + " / ".join(
            replay.stderr_tail[-3:]
        )
        return False
    replay.summary = _summary(done.stdout)
    replay.error = None
    return True


def run(program, path, out_dir, config):
    """Runs swlio-run on the recording at `path` into out_dir; with the incident's
    config.yaml first, and without it when swlio-run refuses that configuration."""
    replay = Replay()
    notes = replay.notes
    if program is None:
        replay.error = "swlio-run not found (beside swlio-report, on PATH or --swlio-run)"
        return replay
    cmd = _command(program, path, out_dir, config)
    if not _run(cmd, replay) and config:
        notes.append(f"replay with config.yaml failed ({replay.error}); replayed with defaults")
        cmd = _command(program, path, out_dir, None)
        _run(cmd, replay)
    replay.command = " ".join(os.path.basename(c) if i == 0 else c for i, c in enumerate(cmd))
    if replay.error is None:
        _read_outputs(replay, out_dir, notes)
    return replay


def _read_outputs(replay, out, notes):
    replay.trajectory = read_tum(f"{out}/traj.tum", notes)
    replay.timings = read_csv(f"{out}/timings.csv", notes)
    replay.diagnostics = read_csv(f"{out}/diagnostics.csv", notes)
    replay.covariance = read_csv(f"{out}/covariance.csv", notes)
    replay.loops = _read_loops(f"{out}/loops.csv", notes)
    replay.map_points, replay.map_total = pointcloud.read_xy(f"{out}/map.pcd", notes)


def _read_loops(path, notes):
    """--loops: candidate_t_ns,node_t_ns,distance_m,verdict,fitness,... (loop_closure_run.cpp)."""
    return read_csv(path, notes, required=("node_t_ns", "verdict"))
