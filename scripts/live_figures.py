#!/usr/bin/python3
"""The figures of one live run of scripts/demo (its WORK folder), as JSON on stdout and as a
Markdown row with --row: what the simulator sent and how late, what the daemon lost, how old
each pose was when a subscriber took it, the accuracy, and the daemon's CPU and memory.

Usage: scripts/live_figures.py WORK [--label TEXT]
                               [--row | --cpu-row | --cpu-header | --age-row | --age-header]

--cpu-row: the daemon's CPU per thread (cores: CPU seconds per second of the drive) and its
peak RSS, as a Markdown row under --cpu-header's. --age-row: the pose age and the p99 of its
three parts (serial delivery, the daemon, DDS transport), under --age-header's.

Pose age is measured from the moment the IMU sample's frame went into the serial line
(WORK/sim/imu_writes.csv, written by the simulator) to the moment swlio-echo took the pose
stamped with that sample (WORK/latency.csv): what the serial adapter's own delivery bursts add
is the sensor's, not ours. The sample of a pose is the one whose true time is nearest to the
pose's stamp once their median offset (the clock model's fixed latency) is removed."""
import csv
import json
import re
import subprocess
import sys

import numpy as np


def sim_stats(work):
    with open(f"{work}/sim.log") as f:
        lines = [l for l in f if l.startswith("{")]
    return json.loads(lines[-1]) if lines else {}


def final_status(work):
    text = open(f"{work}/log/swliod.log").read()
    line = [l for l in text.splitlines() if "final status" in l]
    if not line:
        return {}
    l = line[-1]
    num = lambda pat: int(re.search(pat, l).group(1)) if re.search(pat, l) else None
    return {"lidar_missing_packets": num(r"missing (\d+)"), "imu_gaps": num(r"gaps (\d+)"),
            "imu_checksum_errors": num(r"checksum errors (\d+)"), "drops": num(r"drops (\d+)"),
            "sweeps_skipped": num(r"skipped behind (\d+)"), "reinit": num(r"reinit (\d+)"),
            "lidar_clock_jumps": num(r"clock jumps lidar (\d+)"),
            "imu_clock_jumps": num(r"imu (\d+) \| lag"),
            "degraded_cpu_reports": text.count("degraded: CPU")}


def sample_of_pose(t_sample, stamps):
    """Each pose's IMU sample: the nearest in true time once the median offset is removed."""
    def nearest(t):
        i = np.clip(np.searchsorted(t_sample, t), 1, len(t_sample) - 1)
        return np.where(np.abs(t_sample[i - 1] - t) < np.abs(t_sample[i] - t), i - 1, i)
    offset = np.median(stamps - t_sample[nearest(stamps)])
    return nearest(stamps - offset)


def pose_age(work, latency="latency.csv"):
    writes = np.loadtxt(f"{work}/sim/imu_writes.csv", delimiter=",", skiprows=1, dtype=np.int64)
    t_sample, t_written = writes[:, 0], writes[:, 1]
    stamps, takes = [], []
    with open(f"{work}/{latency}") as f:
        for r in csv.DictReader(f):
            if r["topic"] == "pose":
                stamps.append(int(r["stamp_ns"]))
                takes.append(int(r["receive_steady_ns"]))
    if not stamps:
        return {}
    stamps, takes = np.array(stamps), np.array(takes)
    k = sample_of_pose(t_sample, stamps)
    ok = t_written[k] > 0
    age_ms = (takes[ok] - t_written[k][ok]) * 1e-6
    span_s = (stamps[-1] - stamps[0]) * 1e-9
    return {"poses": int(len(stamps)), "pose_rate_hz": round(len(stamps) / max(span_s, 1e-9), 1),
            "pose_age_ms_p50": round(float(np.percentile(age_ms, 50)), 2),
            "pose_age_ms_p99": round(float(np.percentile(age_ms, 99)), 2),
            "pose_age_ms_max": round(float(age_ms.max()), 2)}


def xbus_sample_ends(path):
    """Byte offset just past each MTData2 frame (Xbus: 0xFA 0xFF MID LEN [EXTLEN] data CS)."""
    data, ends, i = open(path, "rb").read(), [], 0
    while i + 4 < len(data):
        if data[i] != 0xFA or data[i + 1] != 0xFF:
            i += 1
            continue
        n, head = data[i + 3], 4
        if n == 0xFF:
            n, head = (data[i + 4] << 8) | data[i + 5], 6
        if data[i + 2] == 0x36:
            ends.append(i + head + n + 1)
        i += head + n + 1
    return np.array(ends, dtype=np.int64)


def pose_age_parts(work, latency="latency.csv"):
    """Pose age split at the daemon's read of the serial bytes (recording/imu.rx.csv) and at its
    DDS write (the sample's source timestamp in latency.csv): serial delivery (the writer's
    write() to the reader's read(): tty layer and the reader's wake-up), the daemon (read to DDS
    write), and DDS transport to the subscriber's take. Needs the daemon's recording; the k-th
    MTData2 frame in it is the k-th line of imu_writes.csv (the simulator writes nothing else)."""
    try:
        writes = np.loadtxt(f"{work}/sim/imu_writes.csv", delimiter=",", skiprows=1,
                            dtype=np.int64)
        rx = np.loadtxt(f"{work}/recording/imu.rx.csv", delimiter=",", skiprows=1,
                        dtype=np.int64, ndmin=2)
        ends = xbus_sample_ends(f"{work}/recording/imu.xbus")
        manifest = open(f"{work}/recording/manifest.yaml").read()
    except (OSError, ValueError):
        return {}
    scale = float(re.search(r"time_scale: (\S+)", manifest).group(1))
    origin = int(re.search(r"time_origin_ns: (-?\d+)", manifest).group(1))
    n = min(len(ends), len(writes))
    chunk = np.searchsorted(rx[:, 0] + rx[:, 1], ends[:n])  # the read holding each frame's end
    ok = chunk < len(rx)
    t_read_host = origin + (rx[chunk[ok], 2] - origin) / scale
    serial_ms = np.full(len(writes), np.nan)
    serial_ms[:n][ok] = (t_read_host - writes[:n][ok, 1]) * 1e-6
    rows = [r for r in csv.DictReader(open(f"{work}/{latency}")) if r["topic"] == "pose"]
    if not rows:
        return {}
    stamps = np.array([int(r["stamp_ns"]) for r in rows])
    takes = np.array([int(r["receive_steady_ns"]) for r in rows])
    dds_ms = np.array([int(r["transport_ns"]) for r in rows]) * 1e-6
    k = sample_of_pose(writes[:, 0], stamps)
    age_ms = (takes - writes[k, 1]) * 1e-6
    serial = serial_ms[k]
    daemon = age_ms - serial - dds_ms
    p = lambda x: round(float(np.nanpercentile(x, 99)), 2)
    return {"pose_age_serial_ms_p99": p(serial), "pose_age_daemon_ms_p99": p(daemon),
            "pose_age_dds_ms_p99": p(dds_ms)}


def ape(work, build, name):
    try:
        out = subprocess.run([f"{build}/bin/swlio-eval", "ape", "--format", "tum", "--align", "se3",
                              f"{work}/sim/groundtruth.tum", f"{work}/{name}"],
                             capture_output=True, text=True, check=True).stdout
        return float(re.search(r"rmse\s+([\d.]+)", out).group(1))
    except (subprocess.CalledProcessError, FileNotFoundError, AttributeError):
        return None


def cpu_memory(work):
    try:
        rows = [l.split() for l in open(f"{work}/daemon_cpu.txt")]
    except FileNotFoundError:
        return {}
    info = {r[0]: r[1:] for r in rows if r[0] in ("drive_s", "hz", "vmhwm_kb")}
    hz = float(info["hz"][0])
    drive_s = float(info["drive_s"][0])
    threads = {}
    for r in rows:
        if r[0] == "thread":
            threads[r[1]] = threads.get(r[1], 0.0) + (int(r[2]) + int(r[3])) / hz
    total = sum(threads.values())
    return {"cpu_core_avg": round(total / drive_s, 3),
            "cpu_by_thread": {k: round(v / drive_s, 4) for k, v in sorted(threads.items())},
            "peak_rss_mb": round(int(info["vmhwm_kb"][0]) / 1024, 1)}


CPU_THREADS = ["optimizer", "lidar_rx", "imu_rx", "propagator", "publisher", "recorder",
               "loop_closure", "localization"]


def main():
    args = sys.argv[1:]
    work = args[0]
    label = args[args.index("--label") + 1] if "--label" in args else work
    # --latency NAME: another subscriber's latency file in WORK (e.g. a real-time one beside)
    latency = args[args.index("--latency") + 1] if "--latency" in args else "latency.csv"
    build = __file__.rsplit("/scripts/", 1)[0] + "/build"
    s = sim_stats(work)
    fig = {"label": label,
           "imu_bytes_written": s.get("imu_bytes"), "imu_bytes_lost": s.get("imu_bytes_dropped"),
           "imu_bytes_delayed": s.get("imu_bytes_delayed"),
           "imu_backlog_max_wait_ms": s.get("imu_backlog_max_wait_ms"),
           "sim_lateness_ms": s.get("lateness_ms"), "sim_late_sends": s.get("late_sends"),
           "udp_errors": s.get("udp_errors")}
    fig.update(final_status(work))
    fig.update(pose_age(work, latency))
    fig.update(pose_age_parts(work, latency))
    fig["ape_odometry_m"] = ape(work, build, "odometry.tum")
    fig["ape_replay_m"] = ape(work, build, "replay.tum")
    fig.update(cpu_memory(work))
    if "--cpu-header" in args:
        print("| run | cores | " + " | ".join(CPU_THREADS) + " | other (DDS, main) | peak RSS (MB) |")
        print("|---" * (len(CPU_THREADS) + 4) + "|")
        return
    if "--cpu-row" in args:
        by = cpu_memory(work).get("cpu_by_thread", {})
        other = sum(v for k, v in by.items() if k not in CPU_THREADS)
        cells = [f"{by[k]:.3f}" if k in by else "–" for k in CPU_THREADS]
        print(f"| {label} | {cpu_memory(work).get('cpu_core_avg', '–')} | " + " | ".join(cells) +
              f" | {other:.3f} | {cpu_memory(work).get('peak_rss_mb', '–')} |")
        return
    if "--age-header" in args:
        print("| run | pose age p50 / p99 (ms) | p99 of its parts: serial delivery / daemon / DDS "
              "(ms) |\n|---|---|---|")
        return
    if "--age-row" in args:
        g = lambda k: fig.get(k, "–")
        print(f"| {label} | {g('pose_age_ms_p50')} / {g('pose_age_ms_p99')} | "
              f"{g('pose_age_serial_ms_p99')} / {g('pose_age_daemon_ms_p99')} / "
              f"{g('pose_age_dds_ms_p99')} |")
        return
    if "--row" in args:
        g = lambda k: "–" if fig.get(k) is None else fig[k]
        f4 = lambda k: "–" if fig.get(k) is None else f"{fig[k]:.4f}"
        print(f"| {label} | {g('imu_bytes_lost')} | {g('lidar_missing_packets')} | "
              f"{g('lidar_clock_jumps')}/{g('imu_clock_jumps')} | {g('sweeps_skipped')} | "
              f"{f4('ape_odometry_m')} | {f4('ape_replay_m')} | {g('pose_age_ms_p50')} / "
              f"{g('pose_age_ms_p99')} | {g('pose_rate_hz')} | "
              f"{(fig.get('sim_lateness_ms') or {}).get('p99', '–')} / "
              f"{(fig.get('sim_lateness_ms') or {}).get('max', '–')} | {g('cpu_core_avg')} | "
              f"{g('peak_rss_mb')} |")
    else:
        print(json.dumps(fig, indent=1))


if __name__ == "__main__":
    main()
