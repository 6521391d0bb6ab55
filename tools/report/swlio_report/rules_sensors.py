"""Verdict rules for the sensors and their clocks (thresholds in verdicts.py)."""
from . import series
from .verdicts import (
    CLOCK_JUMPS,
    IMU_CHECKSUM_ERRORS,
    IMU_SILENT_S,
    LIDAR_MISSING_FRACTION,
    LIDAR_SILENT_S,
    _events,
    _gap,
    _silence,
    count,
)


def _status_silence(v, ctx, name, unit):
    """Status lines with a zero rate once the sensor had streamed (before that the daemon waits
    for it: only a sensor that never streams fails then)."""
    rows = [(t, r) for t, r in zip(*ctx.ev.get(name)) if r is not None]
    first = next((i for i, (_, r) in enumerate(rows) if r > 0), None)
    if first is None:
        v.add("failed", f"never streamed: 0 {unit} in all {len(rows)} status lines")
        return
    zero = [t for t, r in rows[first:] if r == 0]
    if zero:
        v.add("failed", f"0 {unit} in {len(zero)} status line(s) from {ctx.tl.utc(zero[0])}")


def _lidar_counts(v, ctx):
    ev = ctx.ev
    datagrams, missing = ev.grew("lidar_datagrams"), ev.grew("lidar_missing_packets")
    expected = datagrams + missing
    if ev.has("lidar_missing_packets") and expected > 0:
        fraction = missing / expected
        level = "degraded" if fraction > LIDAR_MISSING_FRACTION else "ok"
        v.add(level, f"{count(missing)} missing packets ({fraction:.2%} of {count(expected)})")
    elif ev.has("lidar_missing_packets"):
        v.add("degraded" if missing > 0 else "ok", f"{count(missing)} missing packets")
    bad = ev.grew("lidar_bad_packets")
    if bad > 0:
        v.add("degraded", f"{count(bad)} bad packets")


def lidar(v, ctx):
    ev = ctx.ev
    if ev.has("lidar_datagrams"):
        _silence(v, ctx, *ev.get("lidar_datagrams"), LIDAR_SILENT_S, "LiDAR")
    elif ev.has("status_sweeps_hz"):
        _status_silence(v, ctx, "status_sweeps_hz", "sweeps/s")
    _lidar_counts(v, ctx)
    _events(v, ctx, ("lidar_silent",), "failed")
    _events(v, ctx, ("lidar_lossy",), "degraded")
    raw = ctx.raw
    if raw is not None and raw.lidar_times:
        if not _gap(v, ctx, raw.lidar_times, LIDAR_SILENT_S, "LiDAR (pcap)"):
            v.add(
                "ok",
                f"{count(len(raw.lidar_times))} packets in lidar.pcap, "
                f"no gap ≥ {LIDAR_SILENT_S:g} s",
            )
    timings = ctx.replay.timings if ctx.replay else None
    if timings is not None and timings.rows:
        times = series.seconds(timings.numbers("t_ns"))
        if not _gap(v, ctx, times, LIDAR_SILENT_S, "sweeps (replay)"):
            v.add(
                "ok",
                f"{count(timings.rows)} sweeps replayed, none more than {LIDAR_SILENT_S:g} s apart",
            )


def imu(v, ctx):
    ev = ctx.ev
    if ev.has("imu_samples"):
        if not _silence(v, ctx, *ev.get("imu_samples"), IMU_SILENT_S, "IMU"):
            v.add("ok", f"{count(ev.grew('imu_samples'))} samples")
    elif ev.has("status_imu_hz"):
        _status_silence(v, ctx, "status_imu_hz", "IMU Hz")
    unplugged = ev.grew("imu_disconnects")
    if unplugged > 0:
        v.add("failed", f"{count(unplugged)} disconnect(s)")
    if ev.has("imu_checksum_errors"):
        errors = ev.grew("imu_checksum_errors")
        v.add(
            "degraded" if errors > IMU_CHECKSUM_ERRORS else "ok", f"{count(errors)} checksum errors"
        )
    _events(v, ctx, ("imu_silent",), "failed")
    _events(v, ctx, ("imu_lossy",), "degraded")
    raw = ctx.raw
    if raw is not None and raw.imu:
        if not _gap(v, ctx, [t for t, _ in raw.imu], IMU_SILENT_S, "IMU (imu.rx.csv)"):
            v.add("ok", f"{count(len(raw.imu))} serial bursts, no gap ≥ {IMU_SILENT_S:g} s")


def _recorded_wall_clock(v, ctx):
    """clock_offsets.csv: each row after the first is a step of the wall clock."""
    from .figures import wall_clock_steps

    steps = wall_clock_steps(ctx.inputs)
    if len(steps) > 1:
        t, ms = max(steps[1:], key=lambda s: abs(s[1]))
        v.add(
            "degraded",
            f"wall clock stepped {len(steps) - 1} time(s), by {ms:+.1f} ms at {ctx.tl.utc(t)}",
        )
    elif steps:
        v.add("ok", "wall clock steady (clock_offsets.csv)")


def clocks(v, ctx):
    ev = ctx.ev
    for sensor in ("lidar", "imu"):
        name = f"{sensor}_clock_jumps"
        if ev.has(name):
            jumps = ev.grew(name)
            first = series.first_increase(*ev.get(name))
            where = f", first at {ctx.tl.utc(first)}" if first is not None else ""
            v.add(
                "degraded" if jumps > CLOCK_JUMPS else "ok",
                f"{count(jumps)} {sensor} clock jumps{where}",
            )
    steps = ev.grew("wall_clock_steps")
    if steps > 0:
        v.add("degraded", f"wall clock stepped {count(steps)} time(s)")
    _recorded_wall_clock(v, ctx)
    _events(v, ctx, ("clock_jump",), "degraded")
    jumps = (ctx.replay.summary.get("clock_jumps") if ctx.replay else None) or {}
    if isinstance(jumps, dict) and jumps:
        total = sum(int(j) for j in jumps.values() if isinstance(j, (int, float)))
        v.add(
            "degraded" if total > CLOCK_JUMPS else "ok",
            f"replay: {jumps.get('lidar', 0)} LiDAR / {jumps.get('imu', 0)} IMU clock jumps",
        )
    for line in ctx.logged("clock: jumped", "wall clock stepped")[:1]:
        v.add("degraded", "log: " + line.message[:80])
