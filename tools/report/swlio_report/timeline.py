"""One time axis for every source: host seconds (the daemon's CLOCK_MONOTONIC, t_ns / 1e9), with
UTC beside it where the input tells the offset (health.csv's utc column, incident.yaml, the
manifest's realtime_minus_monotonic_ns). For a log directory, whose lines carry UTC only, host
time is UTC itself.
"""
import re
import time

from . import logs, series

DEDUPE_S = 10.0  # the same warning again within this many seconds is not marked again


class Mark:
    """An event on the time axis: host seconds, a short label, 'failed'/'degraded'/'info'."""

    def __init__(self, t, label, level, detail=""):
        self.t, self.label, self.level, self.detail = t, label, level, detail


class Timeline:
    def __init__(self, utc_offset, start, end):
        self.utc_offset = utc_offset  # UTC minus host (s), or None
        self.start, self.end = start, end
        self.marks = []

    def utc(self, t):
        """'HH:MM:SS.s' UTC of a host time, or '+N.N s' from the start when unknown."""
        if t is None:
            return "?"
        if self.utc_offset is None:
            return f"+{t - self.start:.1f} s"
        u = t + self.utc_offset
        return time.strftime("%H:%M:%S", time.gmtime(u)) + f".{int((u % 1) * 10)}"

    def utc_full(self, t):
        if t is None:
            return "unknown"
        if self.utc_offset is None:
            return f"host {t:.1f} s"
        u = t + self.utc_offset
        return time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime(u)) + f".{int((u % 1) * 1000):03d}Z"

    def host(self, utc_s):
        return None if self.utc_offset is None else utc_s - self.utc_offset

    def rel(self, t):
        return None if t is None else t - self.start


def _manifest_offset(text):
    m = re.search(r"^realtime_minus_monotonic_ns:\s*(-?\d+)", text or "", re.M)
    return int(m.group(1)) * 1e-9 if m else None


def utc_offset(inputs):
    if inputs.kind == "logdir":
        return 0.0
    h = inputs.health
    if h is not None and h.has("utc"):
        found = series.utc_offset(
            series.seconds(h.numbers("t_ns")),
            [logs.parse_utc(u) if isinstance(u, str) else None for u in h.col("utc")],
        )
        if found is not None:
            return found
    inc = inputs.incident
    if inc is not None and inc.t_event_ns is not None and isinstance(inc.opened_utc, str):
        opened = logs.parse_utc(inc.opened_utc)
        if opened is not None:
            return opened - inc.t_event_ns * 1e-9
    return _manifest_offset(inputs.manifest_text)


def _host_times(inputs, replay, raw):
    ts = []
    if inputs.health is not None:
        ts += series.seconds(inputs.health.numbers("t_ns"))
    ts += [p[0] for p in inputs.odometry or []]
    if replay is not None and replay.timings is not None:
        ts += series.seconds(replay.timings.numbers("t_ns"))
    if raw is not None:
        ts += raw.lidar_times[:1] + raw.lidar_times[-1:] if raw.lidar_times else []
        ts += [raw.imu[0][0], raw.imu[-1][0]] if raw.imu else []
    return [t for t in ts if t is not None]


def build(inputs, replay, raw=None):
    """The time axis: span from the incident, else from every timed source."""
    offset = utc_offset(inputs)
    ts = _host_times(inputs, replay, raw)
    if offset is not None:
        ts += [line.utc_s - offset for line in inputs.log_lines]
    span = inputs.incident.span if inputs.incident else {}
    start = span.get("start_ns") * 1e-9 if isinstance(span.get("start_ns"), int) else None
    end = span.get("end_ns") * 1e-9 if isinstance(span.get("end_ns"), int) else None
    start = start if start is not None else (min(ts) if ts else 0.0)
    end = end if end is not None else (max(ts) if ts else start + 1.0)
    tl = Timeline(offset, start, max(end, start + 1e-3))
    tl.marks = _marks(inputs, tl, replay)
    return tl


DEGRADING = (
    "lidar_lossy",
    "imu_lossy",
    "clock_jump",
    "estimator_behind",
    "queue_drops",
    "localization_ambiguous",
)


def event_level(reason):
    """How an incident reason is drawn: an operator's mark is information, a lossy sensor or a
    late estimator degraded, the rest (silence, divergence, lost, watchdog) failed."""
    if reason == "mark":
        return "info"
    return "degraded" if reason in DEGRADING else "failed"


def _incident_marks(inputs):
    inc = inputs.incident
    if inc is None:
        return []
    return [
        Mark(
            e.t_ns * 1e-9 if e.t_ns is not None else None, e.reason, event_level(e.reason), e.detail
        )
        for e in inc.events
    ]


def _log_marks(inputs, tl):
    out, last = [], {}
    for line in inputs.log_lines:
        if not line.is_problem():
            continue
        t = tl.host(line.utc_s)
        key = line.message[:32]
        if t is None or t - last.get(key, -1e18) < DEDUPE_S:
            continue
        last[key] = t
        level = "failed" if line.level in ("error", "critical") else "degraded"
        out.append(Mark(t, line.message[:60], level, line.message))
    return out


def _replay_marks(replay):
    if replay is None:
        return []
    return [
        Mark(t, f"replay: {reason}", "failed", f"the replay diverged ({reason}) and re-initialized")
        for t, reason in replay.divergences
    ]


def _marks(inputs, tl, replay):
    marks = _incident_marks(inputs)
    if not marks:  # an incident's own events say it best; otherwise the log's warnings
        marks = _log_marks(inputs, tl)
    marks += _replay_marks(replay)
    return sorted((m for m in marks if m.t is not None), key=lambda m: m.t)
