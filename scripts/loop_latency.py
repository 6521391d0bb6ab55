#!/usr/bin/python3
"""Is the IMU-rate output slowed by loop closure? Splits the pose topic's age (IMU stamp →
subscriber take) of a live run by whether the loop-closure thread had just logged a solved loop.

Usage: scripts/loop_latency.py LATENCY.csv SWLIOD.log [--window-s 1.0]
LATENCY.csv: `swlio-echo --latency` (receive_realtime_ns, age_ns per sample); SWLIOD.log: the
daemon's log, whose "loop closure: node …" lines (ISO time with offset) mark each accepted loop
after its graph solve. A pose taken within --window-s before such a line (while the attempt and
solve ran) counts as "during a loop"; prints the age percentiles of both sets as JSON."""
import argparse, datetime, json, re
import numpy as np


def loop_times_ns(log):
    out = []
    for line in open(log):
        if "loop closure: node" not in line:
            continue
        stamp = line.split()[0]
        t = datetime.datetime.strptime(stamp, "%Y-%m-%dT%H:%M:%S.%f%z")
        out.append(int(t.timestamp() * 1e9))
    return np.array(sorted(out), dtype=np.int64)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("latency")
    ap.add_argument("log")
    ap.add_argument("--window-s", type=float, default=1.0)
    a = ap.parse_args()
    d = np.genfromtxt(a.latency, delimiter=",", names=True, dtype=None, encoding=None)
    d = d[d["topic"] == "pose"]
    rx = d["receive_realtime_ns"].astype(np.int64)
    age_ms = d["age_ns"].astype(np.float64) * 1e-6
    loops = loop_times_ns(a.log)
    during = np.zeros(rx.size, dtype=bool)
    w = int(a.window_s * 1e9)
    for t in loops:
        during |= (rx >= t - w) & (rx <= t)
    out = {"loops_logged": int(loops.size)}
    for name, sel in (("during_loop", during), ("otherwise", ~during)):
        v = age_ms[sel]
        out[name] = {"poses": int(v.size)} if v.size == 0 else {
            "poses": int(v.size), "p50_ms": float(np.percentile(v, 50)),
            "p99_ms": float(np.percentile(v, 99)), "max_ms": float(v.max())}
    print(json.dumps(out))


if __name__ == "__main__":
    main()
