#!/usr/bin/python3
"""Checks swlio-run's loop attempts (--loops CSV) against the simulator's ground truth.

Usage: scripts/loop_truth.py LOOPS.csv GROUNDTRUTH.tum [--max-m 0.3] [--max-deg 2]

For every verified candidate, the registered pose of the newer keyframe in the older one's IMU
frame is compared with the truth's relative pose at the two times (nearest ground-truth pose,
which the simulator writes at 200 Hz). An accepted loop off by more than --max-m or --max-deg is
a false loop. Prints one JSON line: accepted, rejected, false accepted, and the errors of the
accepted ones (median and max)."""
import argparse, json
import numpy as np


def quat_to_rot(q):
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def pose(row):
    T = np.eye(4)
    T[:3, :3] = quat_to_rot(row[3:7])
    T[:3, 3] = row[0:3]
    return T


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("loops")
    ap.add_argument("groundtruth")
    ap.add_argument("--max-m", type=float, default=0.3)
    ap.add_argument("--max-deg", type=float, default=2.0)
    a = ap.parse_args()
    gt = np.loadtxt(a.groundtruth)
    gt_t = gt[:, 0]
    loops = np.genfromtxt(a.loops, delimiter=",", names=True, dtype=None, encoding=None)
    loops = np.atleast_1d(loops)

    def truth_at(t_ns):
        k = int(np.argmin(np.abs(gt_t - t_ns * 1e-9)))
        return pose(gt[k, 1:8])

    out = {"attempts": int(loops.size), "accepted": 0, "rejected": 0, "false_accepted": 0,
           "rejected_but_true": 0, "accepted_error_m": [], "accepted_error_deg": []}
    for r in loops:
        want = np.linalg.inv(truth_at(r["candidate_t_ns"])) @ truth_at(r["node_t_ns"])
        got = pose([r["x"], r["y"], r["z"], r["qx"], r["qy"], r["qz"], r["qw"]])
        e = np.linalg.inv(want) @ got
        e_m = float(np.linalg.norm(e[:3, 3]))
        e_deg = float(np.degrees(np.arccos(np.clip((np.trace(e[:3, :3]) - 1) / 2, -1, 1))))
        true_loop = e_m <= a.max_m and e_deg <= a.max_deg
        if r["verdict"] == "accepted":
            out["accepted"] += 1
            out["false_accepted"] += 0 if true_loop else 1
            out["accepted_error_m"].append(e_m)
            out["accepted_error_deg"].append(e_deg)
        else:
            out["rejected"] += 1
            out["rejected_but_true"] += 1 if true_loop else 0
    for k in ("accepted_error_m", "accepted_error_deg"):
        v = out.pop(k)
        out[k.replace("error", "error_median")] = float(np.median(v)) if v else None
        out[k.replace("error", "error_max")] = float(np.max(v)) if v else None
    print(json.dumps(out))


if __name__ == "__main__":
    main()
