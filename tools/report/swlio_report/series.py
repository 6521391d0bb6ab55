"""Time series from cumulative counters: rates, silent stretches, increases.

Times are seconds on the daemon's host clock (CLOCK_MONOTONIC; t_ns / 1e9). Values may be None
(a cell that did not parse); a counter that goes down (a daemon restart) starts over.
"""


def seconds(t_ns_values):
    return [None if t is None else t * 1e-9 for t in t_ns_values]


def _pairs(ts, values):
    return [(t, v) for t, v in zip(ts, values) if t is not None and v is not None]


def rate(ts, counter):
    """(t, per-second rate) between consecutive valid rows, at the later row's time."""
    pts = _pairs(ts, counter)
    out = []
    for (t0, c0), (t1, c1) in zip(pts, pts[1:]):
        if t1 > t0 and c1 >= c0:
            out.append((t1, (c1 - c0) / (t1 - t0)))
    return out


def increase(counter):
    """How much a cumulative counter grew over the span (restarts counted from zero)."""
    vals = [v for v in counter if v is not None]
    grown = 0.0
    for a, b in zip(vals, vals[1:]):
        grown += b - a if b >= a else b
    return grown


def first_increase(ts, counter):
    """Time of the first row where the counter grew, or None."""
    pts = _pairs(ts, counter)
    for (_, c0), (t1, c1) in zip(pts, pts[1:]):
        if c1 > c0:
            return t1
    return None


def _period(pts):
    steps = sorted(b[0] - a[0] for a, b in zip(pts, pts[1:]) if b[0] > a[0])
    return steps[len(steps) // 2] if steps else 1.0


def silences(ts, counter, min_s):
    """Stretches where the counter did not grow: [(start_s, length_s)], length at least min_s.

    With one row a period, rows that did not grow form a stretch of at least (rows × period)
    without data: that lower bound is the length reported. A counter that never grows is one
    stretch over the whole span.
    """
    pts = _pairs(ts, counter)
    if len(pts) < 2:
        return []
    period = _period(pts)
    out, start, rows = [], None, 0
    for (t0, c0), (t1, c1) in zip(pts, pts[1:]):
        if c1 > c0 or c1 < c0:
            if rows and rows * period >= min_s:
                out.append((start, rows * period))
            start, rows = None, 0
        else:
            start = t0 if start is None else start
            rows += 1
    if rows and rows * period >= min_s:
        out.append((start, rows * period))
    return out


def gaps(times, min_s):
    """Stretches between consecutive event times (e.g. sweeps) longer than min_s."""
    ts = sorted(t for t in times if t is not None)
    return [(a, b - a) for a, b in zip(ts, ts[1:]) if b - a > min_s]


def utc_offset(host_s, utc_s):
    """UTC minus host time (s): the median over rows that have both, or None."""
    diffs = sorted(u - h for h, u in zip(host_s, utc_s) if h is not None and u is not None)
    return diffs[len(diffs) // 2] if diffs else None
