#!/usr/bin/python3
"""The soak's figures and plot (scripts/soak writes the inputs into WORK).

Usage: scripts/plot_soak.py WORK [--speed X]
Reads WORK/rss.csv (the daemon's RSS and CPU time every 5 s), WORK/latency.csv (swlio-echo
--latency-summary) and WORK/health.log (swlio-echo --topics health); writes WORK/soak.png and
prints: RSS after the first lap and at the end with the growth rate over the laps after the
first, the deepest queue and the drops, the estimator's sweep age, and the pose latency (age
from the IMU sample's stamp to the subscriber's take, and DDS write → take) per interval,
first hour against the last. Times are simulated hours (wall time × speed)."""
import argparse
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

QUEUE = re.compile(r"(\S+) \((\S+)->(\S+)\)=depth (\d+)/(\d+), high (\d+), dropped (\d+)")
AGE = re.compile(r"sweep_age_s=([0-9.]+)")
STAMP = re.compile(r"^health t=([0-9.]+)")
STATE = re.compile(r"swlio: estimator \S+ \"([^\"]*)\"")
PACKETS = re.compile(r"packets_hz=([0-9.]+)")
WAITING = re.compile(r"sweeps_without_imu_dropped=(\d+)")
SKIPPED = re.compile(r"sweeps_skipped_behind=(\d+)")
SOLVE = re.compile(r"solve_ms=([0-9.]+)")
REINIT = re.compile(r"reinitializations=(\d+)")
MAP_POINTS = re.compile(r"local_map_points=(\d+)")


def count(regex, line):
    m = regex.search(line)
    return int(m.group(1)) if m else 0


def read_health(path):
    """Per health message while the LiDAR streams: time (s, host), deepest queue, total queue
    drops, sweep age, state, sweeps dropped waiting for the IMU, sweeps skipped while behind,
    the last update's time (ms), re-initializations, local map points (nan when not reported)."""
    rows = []
    for line in open(path):
        m = STAMP.match(line)
        packets = PACKETS.search(line)
        if not m or not packets or float(packets.group(1)) <= 0.0:
            continue  # before the first packet or after the last: no sweep to age
        queues = QUEUE.findall(line)
        age = AGE.search(line)
        state = STATE.search(line)
        rows.append((float(m.group(1)),
                     max((int(q[3]) for q in queues), default=0),
                     sum(int(q[6]) for q in queues),
                     float(age.group(1)) if age else np.nan,
                     state.group(1) if state else "?",
                     count(WAITING, line), count(SKIPPED, line),
                     float(SOLVE.search(line).group(1)) if SOLVE.search(line) else np.nan,
                     count(REINIT, line),
                     float(MAP_POINTS.search(line).group(1)) if MAP_POINTS.search(line)
                     else np.nan))
    return rows


def growth_mb_per_h(t_h, rss_mb, from_h):
    keep = t_h >= from_h
    if keep.sum() < 3 or np.ptp(t_h[keep]) <= 0:
        return float("nan")
    return float(np.polyfit(t_h[keep], rss_mb[keep], 1)[0])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("work")
    ap.add_argument("--speed", type=float, default=10.0)
    ap.add_argument("--lap-s", type=float, default=965.7, help="simulated seconds per lap")
    a = ap.parse_args()

    rss = np.genfromtxt(f"{a.work}/rss.csv", delimiter=",", names=True)
    t_h = rss["t_s"] * a.speed / 3600.0
    rss_mb = rss["rss_kb"] / 1024.0
    lap_h = a.lap_s / 3600.0
    lat = np.genfromtxt(f"{a.work}/latency.csv", delimiter=",", names=True, dtype=None,
                        encoding=None)
    pose = lat[lat["topic"] == "pose"]
    odo = lat[lat["topic"] == "odometry"]
    health = read_health(f"{a.work}/health.log")
    h_t = np.array([r[0] for r in health])
    h_t_h = (h_t - h_t[0]) * a.speed / 3600.0 if len(h_t) else h_t
    depth = np.array([r[1] for r in health])
    drops = np.array([r[2] for r in health])
    sweep_age = np.array([r[3] for r in health])
    skipped = np.array([r[6] for r in health])
    map_points = np.array([r[9] for r in health])

    print(f"simulated driving: {t_h[-1]:.2f} h in {rss['t_s'][-1] / 60:.1f} min at {a.speed:g}x")
    after_lap = rss_mb[t_h >= lap_h]
    if len(after_lap):
        print(f"RSS: {after_lap[0]:.1f} MB after the first lap, {rss_mb[-1]:.1f} MB at the end "
              f"(peak {rss['hwm_kb'][-1] / 1024:.1f} MB); growth after the first lap "
              f"{growth_mb_per_h(t_h, rss_mb, lap_h):+.2f} MB per simulated hour")
    cpu = np.diff(rss["cpu_s"]) / np.diff(rss["t_s"])
    print(f"daemon CPU: {100 * np.median(cpu):.0f} % of a core (median of 5 s samples)")
    if len(depth):
        print(f"queues: deepest {depth.max()} (median of the per-message maxima "
              f"{np.median(depth):.0f}); queue drops at the end {drops[-1]}; sweeps dropped "
              f"waiting for the IMU {health[-1][5]}; sweeps skipped while behind "
              f"{health[-1][6]}; re-initializations {health[-1][8]}")
        states = sorted(set(re.sub(r"[0-9.]+ s$", "N s", r[4]) for r in health))
        print(f"sweep age (s, host): median {np.nanmedian(sweep_age):.2f}, "
              f"max {np.nanmax(sweep_age):.2f}; states seen: {states}")
        solve = np.array([r[7] for r in health])
        lap = np.floor(h_t_h / lap_h).astype(int)
        per_lap = [np.nanmean(solve[lap == k]) for k in range(lap.max() + 1) if (lap == k).any()]
        print("update time (ms, the health's last sweep, mean per lap): "
              + " ".join(f"{v:.1f}" for v in per_lap))
        if np.isfinite(map_points).any():
            per_lap = [np.nanmax(map_points[lap == k]) for k in range(lap.max() + 1)
                       if (lap == k).any()]
            print("local map points (most per lap): " + " ".join(f"{v:.0f}" for v in per_lap))
    for name, rows in (("pose", pose), ("odometry", odo)):
        if len(rows) < 2:
            continue
        th = rows["t_s"] * a.speed / 3600.0
        first, last = rows[th <= 1.0], rows[th >= th[-1] - 1.0]
        print(f"{name} age p99 per 10 s (ms): first hour median {np.median(first['age_p99_ms']):.2f}"
              f", last hour {np.median(last['age_p99_ms']):.2f}, worst "
              f"{rows['age_p99_ms'].max():.2f}; DDS write->take p99 median "
              f"{np.median(rows['transport_p99_us']):.0f} us; {int(rows['count'].sum())} samples")

    fig, ax = plt.subplots(4, 1, figsize=(9, 11), sharex=True)
    ax[0].plot(t_h, rss_mb, label="RSS")
    ax[0].plot(t_h, rss["hwm_kb"] / 1024.0, "--", label="peak RSS")
    ax[0].set_ylabel("swliod memory (MB)")
    if np.isfinite(map_points).any():
        twin = ax[0].twinx()
        twin.plot(h_t_h, map_points / 1e3, color="tab:green", lw=0.8, label="local map points")
        twin.set_ylabel("local map (thousand points)")
        twin.set_ylim(bottom=0)
        twin.legend(loc="lower right", fontsize=8)
    ax[1].plot(pose["t_s"] * a.speed / 3600.0, pose["age_p50_ms"], label="pose age p50")
    ax[1].plot(pose["t_s"] * a.speed / 3600.0, pose["age_p99_ms"], label="pose age p99")
    ax[1].plot(odo["t_s"] * a.speed / 3600.0, odo["age_p50_ms"], label="odometry age p50")
    ax[1].set_ylabel("latency (ms, host)")
    ax[1].set_yscale("log")
    ax[2].plot(h_t_h, depth, label="deepest queue (items)")
    ax[2].plot(h_t_h, drops, label="drops (total)")
    ax[2].plot(h_t_h, skipped, label="sweeps skipped while behind (total)")
    ax[2].set_ylabel("queues")
    ax[3].plot(h_t_h, sweep_age, label="sweep age (s, host)")
    ax[3].plot(t_h[1:], cpu, label="daemon CPU (cores)")
    ax[3].set_xlabel(f"simulated driving (h), {a.speed:g}x real time")
    for k in range(1, int(t_h[-1] / lap_h) + 1):
        for axis in ax:
            axis.axvline(k * lap_h, color="0.85", lw=0.8)
    for axis in ax:
        axis.legend(loc="upper right", fontsize=8)
        axis.grid(alpha=0.3)
    ax[0].set_title("swliod soak: loop943 laps (grey lines: lap ends)")
    fig.tight_layout()
    fig.savefig(f"{a.work}/soak.png", dpi=110)
    print(f"plot: {a.work}/soak.png")


if __name__ == "__main__":
    main()
