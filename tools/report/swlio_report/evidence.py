"""Counters and gauges over time from whichever source the input has: health.csv (one row a
second), else the status lines of the log (every logging.status_period_s), each as
{name: (times_s, values)} under health.csv's column names.
"""
from . import logs, series

# health.csv column -> status line field (logs.STATUS_FIELDS) for the same quantity.
STATUS_OF = {
    "lidar_missing_packets": "lidar_missing",
    "imu_checksum_errors": "imu_checksum_errors",
    "lidar_clock_jumps": "lidar_clock_jumps",
    "imu_clock_jumps": "imu_clock_jumps",
    "estimator_reinitializations": "reinit",
    "estimator_operator_resets": "operator_resets",
    "estimator_skipped_behind": "skipped_behind",
    "queue_dropped": "drops",
    "estimator_update_ms": "update_ms",
    "estimator_max_update_ms": "max_update_ms",
}


class Evidence:
    def __init__(self, source):
        self.source = source  # "health.csv", "status lines" or ""
        self.columns = {}  # name -> (times_s, values)
        self.states = ([], [])  # estimator tracking state over time
        self.loc_states = ([], [])  # localization state over time
        self.since_start = False  # counters count from the daemon's start (status lines)

    def has(self, name):
        return name in self.columns and any(v is not None for v in self.columns[name][1])

    def get(self, name):
        return self.columns.get(name, ([], []))

    def grew(self, name):
        """A counter's increase over the span; for status lines, whose counters start with the
        daemon (all of its life is in its log directory), from zero."""
        if not self.has(name):
            return 0.0
        values = self.get(name)[1]
        return series.increase(([0.0] if self.since_start else []) + list(values))

    def maximum(self, name):
        vals = [v for v in self.get(name)[1] if v is not None]
        return max(vals) if vals else None


def from_health(table):
    ev = Evidence("health.csv")
    ts = series.seconds(table.numbers("t_ns"))
    for name in table.header:
        if name not in ("t_ns", "utc", "estimator_tracking", "loc_state"):
            ev.columns[name] = (ts, table.numbers(name))
    ev.states = (ts, [s if isinstance(s, str) else "" for s in table.col("estimator_tracking")])
    ev.loc_states = (ts, [s if isinstance(s, str) else "" for s in table.col("loc_state")])
    return ev


def status_rows(log_lines, timeline):
    """(host time, parsed status fields) of every status line that has a time."""
    out = []
    for line in log_lines:
        fields = logs.parse_status(line.message)
        t = timeline.host(line.utc_s)
        if fields and t is not None:
            out.append((t, fields))
    return out


def from_status(rows):
    ev = Evidence("status lines")
    ev.since_start = True
    ts = [t for t, _ in rows]
    for column, field in STATUS_OF.items():
        ev.columns[column] = (ts, [f.get(field) for _, f in rows])
    for field in (
        "lidar_pkt_hz",
        "sweeps_hz",
        "imu_hz",
        "pose_hz",
        "lag_imu_ms",
        "lag_lidar_ms",
        "lag_pose_ms",
    ):
        ev.columns["status_" + field] = (ts, [f.get(field) for _, f in rows])
    ev.states = (ts, [f.get("state", "") for _, f in rows])
    return ev


def with_divergences(ev):
    """Adds `estimator_divergences`: the re-initializations no operator asked for (an older
    daemon's files have no operator resets: none are subtracted)."""
    ts, reinit = ev.get("estimator_reinitializations")
    resets = ev.get("estimator_operator_resets")[1] or [None] * len(reinit)
    if reinit:
        ev.columns["estimator_divergences"] = (
            ts,
            [None if r is None else r - (o or 0) for r, o in zip(reinit, resets)],
        )
    return ev


def build(inputs, timeline):
    if inputs.health is not None and inputs.health.rows > 0:
        ev = from_health(inputs.health)
    else:
        rows = status_rows(inputs.log_lines, timeline)
        ev = from_status(rows) if rows else Evidence("")
    return with_divergences(ev)
