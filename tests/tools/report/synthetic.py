"""A synthetic black-box incident (health.csv, log.txt, odometry.tum, config.yaml, incident.yaml
as docs/blackbox.md lays them out), optionally beside a simulated recording's files.

The default incident: 40 rows at 1 Hz from host time 100 s (UTC 2026-12-04T14:32:00Z); the
LiDAR is silent for 3 s from 120 s (rows 121, 122, 123 see no datagram); the estimator is
degraded meanwhile; the daemon logs a warning; incident.yaml says lidar_silent at 121 s.
"""
import calendar
import math
import os
import time

HEADER = (
    "t_ns,utc,lidar_datagrams,lidar_bad_packets,lidar_missing_packets,lidar_sweeps,"
    "lidar_clock_offset_ms,lidar_clock_drift_ppm,lidar_clock_jumps,imu_bytes,imu_samples,"
    "imu_checksum_errors,imu_skipped_bytes,imu_disconnects,imu_clock_offset_ms,"
    "imu_clock_drift_ppm,imu_clock_jumps,estimator_tracking,estimator_sweeps,"
    "estimator_update_ms,estimator_max_update_ms,estimator_degenerate_directions,"
    "estimator_reinitializations,estimator_skipped_behind,estimator_imu_only_s,"
    "estimator_map_points,loop_nodes,loop_accepted,loop_rejected,loop_correction_m,loc_state,"
    "loc_tracked,loc_lost,loc_hints,poses,queue_max_fill,queue_dropped,wall_clock_steps,cpu_s,"
    "rss_mb,imu_time_offset_ms,imu_time_offset_sigma_ms,moving_points_removed,"
    "estimator_operator_resets"
)
UTC0 = calendar.timegm(time.strptime("2026-12-04T14:32:00", "%Y-%m-%dT%H:%M:%S"))


def utc_text(host_s, t0_s, ms=True):
    u = UTC0 + (host_s - t0_s)
    text = time.strftime("%Y-%m-%dT%H:%M:%S", time.gmtime(u))
    return text + (f".{int(round((u % 1) * 1000)) % 1000:03d}" if ms else "")


def health_rows(
    t0_s=100.0, rows=40, gap=(20, 3), checksum_at=None, reinit_at=None, reset_at=None
):
    """health.csv text: one row a second from t0_s; `gap` = (first silent row, rows); the
    estimator re-initializes at row `reinit_at` (a divergence) and `reset_at` (an operator's)."""
    lines = [HEADER]
    c = dict(dg=0, sw=0, imu=0, cs=0, reinit=0, resets=0, cpu=0.0, loops=0)
    for i in range(rows):
        silent = gap is not None and gap[0] <= i < gap[0] + gap[1]
        if i > 0 and not silent:
            c["dg"] += 750
            c["sw"] += 10
        c["imu"] += 400 if i > 0 else 0
        c["cs"] += 1 if checksum_at is not None and i == checksum_at else 0
        c["reinit"] += 1 if reinit_at is not None and i == reinit_at else 0
        c["reinit"] += 1 if reset_at is not None and i == reset_at else 0
        c["resets"] += 1 if reset_at is not None and i == reset_at else 0
        c["cpu"] += 0.15
        c["loops"] += 1 if i == rows - 5 else 0
        state = "degraded" if silent else "tracking"
        t = t0_s + i
        lines.append(
            ",".join(
                str(v)
                for v in (
                    int(t * 1e9),
                    utc_text(t, t0_s) + "Z",
                    c["dg"],
                    0,
                    0,
                    c["sw"],
                    0.31 + 0.001 * i,
                    12.5,
                    0,
                    c["imu"] * 180,
                    c["imu"],
                    c["cs"],
                    0,
                    0,
                    -1.2,
                    -3.1,
                    0,
                    state,
                    c["sw"],
                    4.8,
                    9.5,
                    1 if silent else 0,
                    c["reinit"],
                    0,
                    0.0,
                    52000,
                    3 + i // 10,
                    c["loops"],
                    1,
                    0.05 * c["loops"],
                    "",
                    0,
                    0,
                    0,
                    c["imu"],
                    0.02,
                    0,
                    0,
                    round(c["cpu"], 2),
                    88.5,
                    -0.8 - 0.01 * i,
                    "" if i < 5 else 0.3,
                    120 * i,
                    c["resets"],
                )
            )
        )
    return "\n".join(lines) + "\n"


def log_text(t0_s=100.0, rows=40, gap=(20, 3)):
    lines = []
    for i in range(0, rows, 5):
        lines.append(
            (
                t0_s + i + 0.05,
                "info",
                "status tracking | lidar 750 pkt/s 10.0 sweeps/s, "
                "missing 0 | imu 400 Hz, checksum errors 0, gaps 0 | pose 400 Hz | update 4.8 ms "
                "(max 9.5) | drops 0 | skipped behind 0 | reinit 0 (operator resets 0) | "
                "clock jumps lidar 0 imu 0 | "
                "lag p99 imu read 0.3 ms, lidar read 0.2 ms, read to pose 1.1 ms",
            )
        )
    if gap is not None:
        lines.append((t0_s + gap[0] + 1.0, "warn", "lidar: no datagram for 1.0 s"))
        lines.append((t0_s + gap[0] + gap[1] + 0.2, "info", "lidar: datagrams again"))
    lines.append(
        (
            t0_s + rows - 5 + 0.3,
            "info",
            "loop closure: node 31 matches node 2 (3.10 m apart, "
            "fitness 0.12); graph of 32 nodes solved in 21.0 ms, correction now 0.05 m / 0.10 deg",
        )
    )
    lines.sort()
    return "".join(f"{utc_text(t, t0_s)}+0000 {lvl:<5} [4242] {msg}\n" for t, lvl, msg in lines)


def odometry_text(t0_s=100.0, rows=40):
    out = []
    for k in range(rows * 10):
        t = t0_s + k * 0.1
        a = 0.02 * k
        out.append(f"{t:.6f} {10 * math.sin(a):.4f} {10 - 10 * math.cos(a):.4f} 0.0 0 0 0 1\n")
    return "".join(out)


def incident_yaml(t0_s=100.0, rows=40, gap=(20, 3)):
    """lidar_silent a second into the gap; without a gap an operator's mark at row 20."""
    t_event = t0_s + (gap[0] if gap else 19) + 1.0
    reason, detail = (
        ("lidar_silent", "no LiDAR datagram for 1.0 s") if gap else ("mark", "operator")
    )
    return (
        f'format: swlio-incident 1\nswlio_version: "0.1.0 (test)"\nreason: {reason}\n'
        f't_event_ns: {int(t_event * 1e9)}\nopened_utc: "{utc_text(t_event, t0_s)}Z"\n'
        f"span: {{start_ns: {int(t0_s * 1e9)}, end_ns: {int((t0_s + rows - 1) * 1e9)}, "
        f'start_utc: "{utc_text(t0_s, t0_s)}Z", end_utc: "{utc_text(t0_s + rows - 1, t0_s)}Z", '
        f"cut_short: false}}\nevents:\n"
        f'  - {{t_ns: {int(t_event * 1e9)}, utc: "{utc_text(t_event, t0_s)}Z", reason: {reason}, '
        f'detail: "{detail}"}}\n'
    )


def write_incident(folder, t0_s=100.0, rows=40, gap=(20, 3), **health):
    os.makedirs(folder, exist_ok=True)
    files = {
        "health.csv": health_rows(t0_s, rows, gap, **health),
        "log.txt": log_text(t0_s, rows, gap),
        "odometry.tum": odometry_text(t0_s, rows),
        "incident.yaml": incident_yaml(t0_s, rows, gap),
        "config.yaml": "lidar:\n  model: rs16\nestimator:\n  mode: tightly-coupled\n",
    }
    for name, text in files.items():
        with open(os.path.join(folder, name), "w") as f:
            f.write(text)
    return folder


def write_logdir(folder, minutes=3):
    """swliod.log and swliod.1.log: status lines every 5 s from 14:34:00Z, a CPU shortage (sweeps
    skipped) at 14:35:00, a LiDAR clock jump at 14:35:30, queue drops at 14:36:00."""
    os.makedirs(folder, exist_ok=True)
    lines, skipped, jumps, drops = [], 0, 0, 0
    for k in range(minutes * 12):
        t = k * 5.0
        skipped += 4 if t == 60 else 0
        jumps += 1 if t == 90 else 0
        drops += 12 if t == 120 else 0
        lines.append(
            (
                t,
                "info",
                f"status tracking | lidar 750 pkt/s 10.0 sweeps/s, missing 0 | imu 400 "
                f"Hz, checksum errors 0, gaps 0 | pose 400 Hz | update 5.1 ms "
                f"(max {9 + k % 3}.0) | drops {drops} | skipped behind {skipped} | reinit 0 | "
                f"clock jumps lidar {jumps} imu 0 | lag p99 imu read 0.3 ms, lidar read 0.2 ms, "
                f"read to pose {1 + k % 4}.1 ms",
            )
        )
        if t == 60:
            lines.append(
                (
                    t,
                    "warn",
                    "degraded: CPU: 4 sweeps skipped since the last status (the "
                    "estimator fell behind the LiDAR); the IMU-rate pose continues.",
                )
            )
        if t == 90:
            lines.append(
                (
                    t,
                    "warn",
                    "lidar clock: jumped 1 time(s) since the last status (1 in all); "
                    "offset now 1.100000 s, drift 3.0 ppm.",
                )
            )
        if t == 120:
            lines.append(
                (
                    t,
                    "warn",
                    "queue lidar_packets (lidar -> optimizer): 12 dropped, high water 64/64",
                )
            )
    text = "".join(
        f"{utc_text(100.0 + t, 100.0 - 120.0)}+0000 {lvl:<5} [77] {msg}\n" for t, lvl, msg in lines
    )
    half = len(text.splitlines(True)) // 2
    rows = text.splitlines(True)
    with open(os.path.join(folder, "swliod.1.log"), "w") as f:
        f.writelines(rows[:half])
    with open(os.path.join(folder, "swliod.log"), "w") as f:
        f.writelines(rows[half:])
    return folder
