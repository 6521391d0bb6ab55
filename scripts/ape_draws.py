"""Draws of swlio-run on one recording, and simulated recordings made once, shared by
scripts/ape-spread, scripts/time-offset-eval and scripts/ape-realizations.

A draw is swlio-run with the floor under a sweep's LiDAR position sigma (--lidar-floor-m,
0.01 m) scaled by 1 + k * 1e-5 for draw k = 0 .. N-1 (draw 0: unchanged). swlio-run is
deterministic for one input and configuration, but a change in the last digits takes another
path through the nonlinear solves, the map insertions and the feature choices: the spread of the
draws is the resolution of any comparison of single runs (bench/README, "The field").

SWLIO_BIN_DIR (default build/bin) holds swlio-sim, swlio-run and swlio-eval."""
import concurrent.futures
import json
import os
import shutil
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.environ.get("SWLIO_BIN_DIR", os.path.join(ROOT, "build", "bin"))
STEP = 1e-5  # relative change of the floor per draw
FLOOR_M = 0.01  # swlio-run's default --lidar-floor-m


class RunError(Exception):
    pass


def floors(base_m, draws):
    return [base_m * (1.0 + k * STEP) for k in range(draws)]


def call(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        tail = "\n".join((r.stdout + r.stderr).strip().splitlines()[-5:])
        raise RunError(f"{' '.join(cmd)} exited with {r.returncode}:\n{tail}")
    return r.stdout


def simulate_once(rec, args):
    """The recording `rec`, made with swlio-sim `args` unless it is there (made into REC.part,
    then renamed: an interrupted one is made again)."""
    if not os.path.isdir(rec):
        part = rec + ".part"
        shutil.rmtree(part, ignore_errors=True)
        call([os.path.join(BIN, "swlio-sim"), "--out", part] + args)
        os.replace(part, rec)
    return rec


def ape_rmse(gt, est):
    """APE RMSE (m) of a TUM trajectory against the ground truth, SE(3) alignment."""
    out = call([os.path.join(BIN, "swlio-eval"), "ape", gt, est, "--format", "tum",
                "--align", "se3", "--json"])
    try:
        return float(json.loads(out)["rmse"])
    except (ValueError, KeyError, TypeError) as e:
        raise RunError(f"no rmse in swlio-eval's output for {est} ({e})") from e


def run_draw(rec, out, floor_m, extra):
    """swlio-run on `rec` with this floor (loop closure off unless `extra` sets it) into `out`;
    the APE of `out`."""
    args = [os.path.join(BIN, "swlio-run"), rec, "--out", out, "--lidar-floor-m", repr(floor_m)]
    if "--loop-closure" not in extra:
        args += ["--loop-closure", "off"]
    call(args + extra)
    return ape_rmse(os.path.join(rec, "groundtruth.tum"), out)


def run_all(tasks, jobs):
    """{key: result} for {key: (function, args...)}, `jobs` at a time; the first failure raised."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {key: pool.submit(*task) for key, task in tasks.items()}
        return {key: f.result() for key, f in futures.items()}
