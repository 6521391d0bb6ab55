"""The daemon's log lines (daemon/src/runtime/logging.cpp's pattern) and its status lines
(daemon/src/runtime/health.cpp, StatusLine).

A line: `2026-12-04T14:32:07.120+0000 info  [1234] message`. Lines that do not parse (a line
cut by a crash, garbage) are counted, never fatal.
"""
import calendar
import glob
import os
import re
import time

_TIME = r"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d)(\.\d+)?(Z|[+-]\d\d:?\d\d)?"
_LINE = re.compile(r"^" + _TIME + r"\s+([A-Za-z]+)\s+\[(\d+)\]\s?(.*)$")
_LEVELS = {
    "trace": "trace",
    "debug": "debug",
    "info": "info",
    "warn": "warn",
    "warning": "warn",
    "error": "error",
    "err": "error",
    "critical": "critical",
}

# Status line fields: name -> regex of the number (cumulative counters and rates alike).
STATUS_FIELDS = {
    "lidar_pkt_hz": r"lidar ([\d.]+) pkt/s",
    "sweeps_hz": r"([\d.]+) sweeps/s",
    "lidar_missing": r"missing (\d+)",
    "imu_hz": r"imu ([\d.]+) Hz",
    "imu_checksum_errors": r"checksum errors (\d+)",
    "imu_gaps": r"gaps (\d+)",
    "pose_hz": r"pose ([\d.]+) Hz",
    "update_ms": r"update ([\d.]+) ms",
    "max_update_ms": r"\(max ([\d.]+)\)",
    "drops": r"drops (\d+)",
    "skipped_behind": r"skipped behind (\d+)",
    "reinit": r"reinit (\d+)",
    "operator_resets": r"operator resets (\d+)",
    "lidar_clock_jumps": r"clock jumps lidar (\d+)",
    "imu_clock_jumps": r"clock jumps lidar \d+ imu (\d+)",
    "lag_imu_ms": r"imu read ([\d.]+) ms",
    "lag_lidar_ms": r"lidar read ([\d.]+) ms",
    "lag_pose_ms": r"read to pose ([\d.]+) ms",
}
# Fields newer daemons added (2026-12-05); an older daemon's lines lack them.
NEWER_STATUS_FIELDS = {"operator_resets"}
_STATUS_FIELDS = {k: re.compile(v) for k, v in STATUS_FIELDS.items()}
_STATUS = re.compile(r"^(final )?status (\w+)")


class LogLine:
    """One parsed line: UTC seconds since the epoch, level (info, warn, error, ...), message."""

    def __init__(self, utc_s, level, tid, message, source=""):
        self.utc_s, self.level, self.tid, self.message = utc_s, level, tid, message
        self.source = source

    def is_problem(self):
        return self.level in ("warn", "error", "critical")


def _offset_s(zone):
    if not zone or zone == "Z":
        return 0
    sign = -1 if zone[0] == "-" else 1
    digits = zone[1:].replace(":", "")
    return sign * (int(digits[:2]) * 3600 + int(digits[2:4]) * 60)


def parse_utc(text):
    """ISO 8601 time (`2026-12-04T14:32:07.120Z` or `+0000`) to UTC epoch seconds, or None."""
    m = re.match(r"^" + _TIME + r"$", text.strip())
    if not m:
        return None
    return _epoch(m.group(1), m.group(2), m.group(3))


def _epoch(base, fraction, zone):
    try:
        t = calendar.timegm(time.strptime(base, "%Y-%m-%dT%H:%M:%S"))
    except ValueError:
        return None
    return t + float(fraction or 0) - _offset_s(zone)


def parse_line(text, source=""):
    """A LogLine, or None when the text is not a log line."""
    m = _LINE.match(text.rstrip("\r\n"))
    if not m or m.group(4).lower() not in _LEVELS:
        return None
    t = _epoch(m.group(1), m.group(2), m.group(3))
    if t is None:
        return None
    return LogLine(t, _LEVELS[m.group(4).lower()], int(m.group(5)), m.group(6), source)


def parse_lines(text, source, notes):
    """Every log line of a file's text; unparsed lines are counted in one note."""
    lines, bad = [], 0
    for raw in text.splitlines():
        if not raw.strip():
            continue
        line = parse_line(raw, source)
        if line is None:
            bad += 1
        else:
            lines.append(line)
    if bad:
        notes.append(f"{source}: {bad} line(s) that are not log lines skipped")
    return lines


def log_files(directory):
    """swliod.log and its rotated files (swliod.1.log, ...), oldest first."""

    def rank(path):
        m = re.search(r"\.(\d+)\.log$", path)
        return -(int(m.group(1)) if m else 0)

    files = glob.glob(os.path.join(directory, "*.log")) + glob.glob(
        os.path.join(directory, "*.log.*")
    )
    return sorted(set(files), key=rank)


def parse_status(message):
    """A status line's state and numbers ({} for other lines)."""
    m = _STATUS.match(message)
    if not m:
        return {}
    fields = {"state": m.group(2), "final": bool(m.group(1))}
    for name, pattern in _STATUS_FIELDS.items():
        found = pattern.search(message)
        if found:
            fields[name] = float(found.group(1))
    return fields
