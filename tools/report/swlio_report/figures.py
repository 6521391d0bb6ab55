"""The time plots of the page, each from whichever source has the quantity (health.csv, the
log's status lines, the recording's raw files, the replay). A figure without data is None and
its section says what is absent.
"""
import math

from . import raw_sensors, series
from .rules_system import cpu_percent
from .svg_plot import time_plot


class Figures:
    """Builds plots on the timeline's axis (seconds since the span's start)."""

    def __init__(self, ctx):
        self.ctx, self.tl = ctx, ctx.tl
        t0 = self.tl.start
        self.x_range = (0.0, self.tl.end - t0)
        self.events = [(m.t - t0, m.label, m.level) for m in self.tl.marks]
        self.xlabel = f"s since {self.tl.utc_full(t0)}" if self.tl.utc_offset is not None else "s"

    def rel(self, pts):
        t0 = self.tl.start
        return [(t - t0, v) for t, v in pts if t is not None and v is not None]

    def column(self, name, scale=1.0):
        ts, vals = self.ctx.ev.get(name)
        return self.rel((t, None if v is None else v * scale) for t, v in zip(ts, vals))

    def rate(self, name):
        return self.rel(series.rate(*self.ctx.ev.get(name))) if self.ctx.ev.has(name) else []

    def grown(self, name):
        """A cumulative counter as its increase since the span's first row."""
        pts = self.column(name)
        return [(t, v - pts[0][1]) for t, v in pts] if pts else []

    def plot(self, series_list, title, ylabel, floor_zero=True):
        series_list = [s for s in series_list if s["points"]]
        if not series_list:
            return None
        return time_plot(
            series_list,
            title,
            ylabel,
            self.xlabel,
            self.x_range,
            self.events,
            floor_zero=floor_zero,
        )

    def replay_column(self, table_name, column, scale=1.0):
        table = getattr(self.ctx.replay, table_name, None) if self.ctx.replay else None
        if table is None:
            return []
        ts = series.seconds(table.numbers("t_ns"))
        return self.rel(
            (t, None if v is None else v * scale) for t, v in zip(ts, table.numbers(column))
        )


def sensor_rates(f):
    lidar = f.rate("lidar_datagrams") or f.column("status_lidar_pkt_hz")
    imu = f.rate("imu_samples") or f.column("status_imu_hz")
    sweeps = f.rate("lidar_sweeps") or f.column("status_sweeps_hz")
    timings = f.ctx.replay.timings if f.ctx.replay else None
    if not sweeps and timings is not None:
        sweeps = f.rel(raw_sensors.per_second(series.seconds(timings.numbers("t_ns"))))
    raw = f.ctx.raw
    if not lidar and raw is not None and raw.lidar_times:
        lidar = f.rel(raw_sensors.per_second(raw.lidar_times))
    if not imu and raw is not None and raw.imu:
        imu = f.rel(raw_sensors.per_second([t for t, _ in raw.imu]))
        imu_label = "IMU serial bursts/s (imu.rx.csv)"
    else:
        imu_label = "IMU samples/s"
    return [
        f.plot([{"label": "LiDAR packets/s", "points": lidar}], "LiDAR packet rate", "packets/s"),
        f.plot([{"label": imu_label, "points": imu, "color": "#2ca02c"}], "IMU rate", "per s"),
        f.plot(
            [{"label": "sweeps/s", "points": sweeps, "color": "#9467bd"}],
            "LiDAR sweep rate",
            "sweeps/s",
        ),
    ]


def sensor_errors(f):
    names = [
        ("lidar_missing_packets", "LiDAR missing"),
        ("lidar_bad_packets", "LiDAR bad"),
        ("imu_checksum_errors", "IMU checksum errors"),
        ("imu_skipped_bytes", "IMU skipped bytes"),
        ("imu_disconnects", "IMU disconnects"),
    ]
    return f.plot(
        [{"label": label, "points": f.grown(n), "step": True} for n, label in names],
        "Sensor errors (increase over the span)",
        "count",
    )


def clock_plots(f):
    offsets = f.plot(
        [
            {"label": "LiDAR offset", "points": f.column("lidar_clock_offset_ms")},
            {"label": "IMU offset", "points": f.column("imu_clock_offset_ms")},
        ],
        "Sensor clock offset to host",
        "ms",
        floor_zero=False,
    )
    drift = f.plot(
        [
            {"label": "LiDAR drift", "points": f.column("lidar_clock_drift_ppm")},
            {"label": "IMU drift", "points": f.column("imu_clock_drift_ppm")},
        ],
        "Sensor clock drift",
        "ppm",
        floor_zero=False,
    )
    jumps = f.plot(
        [
            {"label": "LiDAR clock jumps", "points": f.grown("lidar_clock_jumps"), "step": True},
            {"label": "IMU clock jumps", "points": f.grown("imu_clock_jumps"), "step": True},
            {"label": "wall-clock steps", "points": f.grown("wall_clock_steps"), "step": True},
        ],
        "Clock jumps (increase over the span)",
        "count",
    )
    time_offset = f.plot(
        [
            {"label": "applied", "points": f.column("imu_time_offset_ms")},
            {"label": "sigma", "points": f.column("imu_time_offset_sigma_ms"), "color": "#7f7f7f"},
        ],
        "LiDAR-IMU time offset (IMU stamps late by)",
        "ms",
        floor_zero=False,
    )
    return [offsets, drift, time_offset, jumps, wall_clock_plot(f)]


def wall_clock_steps(inputs):
    """[(host s, realtime − monotonic change since the first row, ms)] of clock_offsets.csv
    (swliod --record: a row at the start and at each change of the wall clock)."""
    table = inputs.clock_offsets
    if table is None:
        return []
    rows = [
        (t * 1e-9, o)
        for t, o in zip(
            table.numbers("t_monotonic_ns"), table.numbers("realtime_minus_monotonic_ns")
        )
        if t is not None and o is not None
    ]
    return [(t, (o - rows[0][1]) * 1e-6) for t, o in rows]


def wall_clock_plot(f):
    steps = wall_clock_steps(f.ctx.inputs)
    if len(steps) > 1:
        steps = steps + [(f.tl.end, steps[-1][1])]  # the last offset holds to the end
    return f.plot(
        [{"label": "wall clock − monotonic", "points": f.rel(steps), "step": True}],
        "Wall clock against the monotonic clock (clock_offsets.csv), change since the start",
        "ms",
        floor_zero=False,
    )


def _sigma(f, indices, scale=1.0):
    table = f.ctx.replay.covariance if f.ctx.replay else None
    if table is None:
        return []
    ts = series.seconds(table.numbers("t_ns"))
    cols = [table.numbers(f"P_{i}_{i}") for i in indices]
    out = []
    for k, t in enumerate(ts):
        vals = [c[k] for c in cols]
        if t is not None and all(v is not None and v >= 0 for v in vals):
            out.append((t, math.sqrt(sum(vals)) * scale))
    return f.rel(out)


def estimator_plots(f):
    update = f.plot(
        [
            {
                "label": "replay total (thread CPU)",
                "points": f.replay_column("timings", "total_ms"),
            },
            {"label": "daemon update", "points": f.column("estimator_update_ms")},
            {"label": "daemon max update", "points": f.column("estimator_max_update_ms")},
        ],
        "Per-sweep update time",
        "ms",
    )
    iterations = f.plot(
        [
            {
                "label": "solver iterations",
                "points": f.replay_column("diagnostics", "iterations"),
                "marker": True,
            }
        ],
        "Solver iterations per sweep (replay)",
        "iterations",
    )
    degenerate = f.plot(
        [
            {
                "label": "degenerate directions (replay)",
                "points": f.replay_column("diagnostics", "degenerate_directions"),
                "step": True,
            },
            {
                "label": "degenerate directions (daemon)",
                "points": f.column("estimator_degenerate_directions"),
                "step": True,
            },
        ],
        "Degeneracy",
        "directions",
    )
    sigma = f.plot(
        [
            {"label": "position σ (m)", "points": _sigma(f, (0, 1, 2))},
            {"label": "yaw σ (deg)", "points": _sigma(f, (5,), 180.0 / math.pi)},
        ],
        "Marginal covariance of the newest state (replay)",
        "σ",
    )
    return [update, iterations, degenerate, sigma]


def loop_plots(f):
    counts = f.plot(
        [
            {"label": "loops accepted", "points": f.grown("loop_accepted"), "step": True},
            {"label": "loops rejected", "points": f.grown("loop_rejected"), "step": True},
            {"label": "relocalizations (hints)", "points": f.grown("loc_hints"), "step": True},
            {"label": "localization lost", "points": f.grown("loc_lost"), "step": True},
            {"label": "loops accepted (replay)", "points": _replay_loop_count(f), "step": True},
        ],
        "Loop closures and relocalizations (daemon)",
        "count",
    )
    correction = f.plot(
        [
            {"label": "loop correction (daemon)", "points": f.column("loop_correction_m")},
            {
                "label": "accepted loops' correction (replay)",
                "points": _replay_loops(f),
                "marker": True,
            },
        ],
        "Loop-closure correction",
        "m",
    )
    return [counts, correction]


def _replay_loop_count(f):
    """Accepted loops of the replay, cumulative at each accepting node's time."""
    times = sorted(t for t, _ in _replay_loops(f))
    return [(t, float(i + 1)) for i, t in enumerate(times)]


def _replay_loops(f):
    loops = f.ctx.replay.loops if f.ctx.replay else None
    if loops is None:
        return []
    pts = [
        (t * 1e-9, c)
        for t, c, v in zip(
            loops.numbers("node_t_ns"), loops.numbers("correction_m"), loops.col("verdict")
        )
        if v == "accepted" and t is not None
    ]
    return f.rel(pts)


def system_plots(f):
    cpu = f.plot([{"label": "CPU % of a core", "points": f.rel(cpu_percent(f.ctx.ev))}], "CPU", "%")
    rss = f.plot(
        [{"label": "RSS", "points": f.column("rss_mb"), "color": "#8c564b"}], "Memory", "MB"
    )
    queues = f.plot(
        [
            {"label": "fullest queue (%)", "points": f.column("queue_max_fill", 100.0)},
            {"label": "queue drops", "points": f.grown("queue_dropped"), "step": True},
            {
                "label": "skipped behind",
                "points": f.grown("estimator_skipped_behind"),
                "step": True,
            },
        ],
        "Queues",
        "% / count",
    )
    lag = f.plot(
        [
            {"label": "IMU read lag p99", "points": f.column("status_lag_imu_ms")},
            {"label": "LiDAR read lag p99", "points": f.column("status_lag_lidar_ms")},
            {"label": "read to pose p99", "points": f.column("status_lag_pose_ms")},
        ],
        "Latency (status lines)",
        "ms",
    )
    return [cpu, rss, queues, lag]
