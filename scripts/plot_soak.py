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


def read_health(path):
    """Per health message while the LiDAR streams: time (s, host), deepest queue, total queue
    drops, sweep age, state, sweeps dropped waiting for the IMU."""
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
                     int(WAITING.search(line).group(1)) if WAITING.search(line) else 0))
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
              f"waiting for the IMU {health[-1][5]}")
        print(f"sweep age (s, host): median {np.nanmedian(sweep_age):.2f}, "
              f"max {np.nanmax(sweep_age):.2f}; states seen: "
              f"{sorted(set(r[4] for r in health))}")
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
    ax[1].plot(pose["t_s"] * a.speed / 3600.0, pose["age_p50_ms"], label="pose age p50")
    ax[1].plot(pose["t_s"] * a.speed / 3600.0, pose["age_p99_ms"], label="pose age p99")
    ax[1].plot(odo["t_s"] * a.speed / 3600.0, odo["age_p50_ms"], label="odometry age p50")
    ax[1].set_ylabel("latency (ms, host)")
    ax[1].set_yscale("log")
    ax[2].plot(h_t_h, depth, label="deepest queue (items)")
    ax[2].plot(h_t_h, drops, label="drops (total)")
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
