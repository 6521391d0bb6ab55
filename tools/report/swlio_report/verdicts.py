"""A verdict per subsystem: ok / degraded / failed with the reason in one line, or 'no data'.

Each rule reads the evidence (health.csv, else the log's status lines), the incident's events,
the raw receive times of a recording, and the replay. The thresholds below are printed in the
page (docs/report.md lists them too).
"""
from . import series

LIDAR_MISSING_FRACTION = 0.001  # missing / expected packets above this: degraded (0.1 %)
LIDAR_SILENT_S = 1.0  # no LiDAR packet for this long: failed
IMU_SILENT_S = 1.0  # no IMU sample (serial burst) for this long: failed
IMU_CHECKSUM_ERRORS = 0  # more checksum errors than this: degraded
CLOCK_JUMPS = 0  # more clock jumps (either sensor) or wall-clock steps: degraded
REINITIALIZATIONS = 0  # more re-initializations (divergence) than this: failed
UPDATE_MS = 100.0  # a sweep's update slower than the sweep period: degraded
SKIPPED_BEHIND = 0  # more sweeps shed behind than this: degraded
QUEUE_DROPS = 0  # more queue drops than this: degraded
QUEUE_FILL = 0.8  # the fullest queue above this fraction: degraded
HEALTH_GAP_S = 2.5  # health.csv rows further apart than this: the black box lost rows

LEVELS = ("ok", "degraded", "failed")
SUBSYSTEMS = (
    "LiDAR",
    "IMU",
    "clocks",
    "estimator",
    "loop closure / localization",
    "CPU / queues",
    "black box",
)

THRESHOLDS = [
    (
        "LiDAR",
        f"degraded: missing packets > {LIDAR_MISSING_FRACTION:.1%} or bad packets > 0; "
        f"failed: silent ≥ {LIDAR_SILENT_S:g} s",
    ),
    (
        "IMU",
        f"degraded: checksum errors > {IMU_CHECKSUM_ERRORS}; failed: silent ≥ {IMU_SILENT_S:g} s "
        "or a disconnect",
    ),
    ("clocks", f"degraded: clock jumps > {CLOCK_JUMPS} (LiDAR or IMU) or wall-clock steps > 0"),
    (
        "estimator",
        f"failed: re-initializations > {REINITIALIZATIONS} or state lost; degraded: "
        f"state degraded, match failures, update > {UPDATE_MS:g} ms",
    ),
    ("loop closure / localization", "failed: localization lost; degraded: ambiguous"),
    (
        "CPU / queues",
        f"degraded: skipped behind > {SKIPPED_BEHIND}, queue drops > {QUEUE_DROPS}, "
        f"fullest queue > {QUEUE_FILL:.0%}",
    ),
    (
        "black box",
        f"degraded: span cut short, a black-box file absent or malformed, health rows "
        f"> {HEALTH_GAP_S:g} s apart",
    ),
]


class Verdict:
    def __init__(self, subsystem):
        self.subsystem, self.level, self.findings = subsystem, None, []

    def add(self, level, reason):
        """The verdict is the worst level added; every finding is kept."""
        if self.level is None or LEVELS.index(level) > LEVELS.index(self.level):
            self.level = level
        self.findings.append((level, reason))

    def reason(self):
        """The worst findings first, at most three, in one line."""
        ordered = sorted(self.findings, key=lambda f: -LEVELS.index(f[0]))
        return "; ".join(r for _, r in ordered[:3]) if ordered else self.missing

    missing = "no data: the input has nothing on it"

    def label(self):
        return self.level or "no data"


class Context:
    """What the rules read; see main.py for how it is built."""

    def __init__(self, inputs, evidence, timeline, replay=None, raw=None):
        self.inputs, self.ev, self.tl, self.replay, self.raw = (
            inputs,
            evidence,
            timeline,
            replay,
            raw,
        )

    def events(self, *reasons):
        inc = self.inputs.incident
        return [e for e in (inc.events if inc else []) if e.reason in reasons]

    def logged(self, *needles):
        return [
            line
            for line in self.inputs.log_lines
            if line.is_problem() and any(n in line.message for n in needles)
        ]


def count(n):
    return f"{int(n):,}"


def _events(v, ctx, reasons, level):
    for e in ctx.events(*reasons):
        when = ctx.tl.utc(e.t_ns * 1e-9) if e.t_ns is not None else "?"
        v.add(level, f"incident: {e.reason} at {when}" + (f" ({e.detail})" if e.detail else ""))


def _silence(v, ctx, ts, values, min_s, what):
    found = series.silences(ts, values, min_s)
    if found:
        start, length = max(found, key=lambda s: s[1])
        more = f" ({len(found)} stretches)" if len(found) > 1 else ""
        v.add("failed", f"{what} silent ≥ {length:.1f} s from {ctx.tl.utc(start)}{more}")
    return bool(found)


def _gap(v, ctx, times, min_s, what):
    found = series.gaps(times, min_s)
    if found:
        start, length = max(found, key=lambda s: s[1])
        v.add("failed", f"{what} silent {length:.2f} s from {ctx.tl.utc(start)}")
    return bool(found)


def from_modules():
    """Every rule function, in SUBSYSTEMS order (imported late: the rules live in rules_*.py)."""
    from . import rules_sensors, rules_system

    return [
        rules_sensors.lidar,
        rules_sensors.imu,
        rules_sensors.clocks,
        rules_system.estimator,
        rules_system.localization,
        rules_system.cpu_queues,
        rules_system.black_box,
    ]


def judge(ctx):
    """[Verdict] in SUBSYSTEMS order."""
    out = []
    for name, rule in zip(SUBSYSTEMS, from_modules()):
        v = Verdict(name)
        if not ctx.ev.source:
            v.missing = "no data: no health.csv and no status lines in this input"
        rule(v, ctx)
        out.append(v)
    return out
