"""Inline SVG plots without any library: time plots (lines, steps, markers, event lines) and
a top view (points, paths, labelled marks) with equal axes. Text stays text (searchable).
"""
import math
from html import escape

COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#17becf"]
EVENT_COLOR = {"failed": "#c0392b", "degraded": "#d68910", "info": "#7f8c8d"}
W, H = 880, 180  # a time plot's size (px)
MAX_POINTS = 1600  # per series: longer ones keep each pixel column's min and max
PAD_L, PAD_R, PAD_T, PAD_B = 62, 14, 24, 30


def nice_ticks(lo, hi, count=6):
    """Round tick values covering [lo, hi]."""
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo:
        return [lo]
    raw = (hi - lo) / count
    mag = 10 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 2.5, 5, 10) if m * mag >= raw)
    first = math.ceil(lo / step) * step
    return [first + i * step for i in range(int((hi - first) / step) + 1)]


def _fmt(v):
    if v == 0:
        return "0"
    if abs(v) >= 1000 or abs(v) < 0.01:
        return f"{v:.3g}"
    return f"{v:.6g}" if v == int(v) else f"{v:.3g}"


class Frame:
    """Maps data coordinates to pixels inside a plot area."""

    def __init__(self, x_range, y_range, width, height, pads):
        self.x0, self.x1 = x_range
        self.y0, self.y1 = y_range
        self.left, self.right, self.top, self.bottom = pads
        self.width, self.height = width, height

    def px(self, x):
        span = (self.x1 - self.x0) or 1.0
        return self.left + (x - self.x0) / span * (self.width - self.left - self.right)

    def py(self, y):
        span = (self.y1 - self.y0) or 1.0
        return (
            self.height
            - self.bottom
            - (y - self.y0) / span * (self.height - self.top - self.bottom)
        )


def _range(values, pad=0.05, floor_zero=False):
    vals = [v for v in values if v is not None and math.isfinite(v)]
    if not vals:
        return 0.0, 1.0
    lo, hi = min(vals), max(vals)
    if floor_zero and lo >= 0:
        lo = 0.0
        if hi < 1e-12:
            return 0.0, 1.0
    if hi - lo < 1e-12:
        lo, hi = lo - 0.5 if lo else -0.5, hi + 0.5 if hi else 0.5
    d = (hi - lo) * pad
    return (lo if floor_zero and lo == 0 else lo - d), hi + d


def decimate(points, max_points=MAX_POINTS):
    """At most about max_points of a series sorted by x: per bucket of x its lowest and highest
    point, in x order, so that spikes stay visible. None values (breaks) are kept."""
    if len(points) <= max_points:
        return points
    buckets = max_points // 2
    x0, x1 = points[0][0], points[-1][0]
    width = (x1 - x0) / buckets or 1.0
    out, current, key = [], [], None
    for p in points:
        k = int((p[0] - x0) / width)
        if k != key and current:
            out += _extremes(current)
            current = []
        key = k
        current.append(p)
    return out + _extremes(current)


def _extremes(bucket):
    valid = [p for p in bucket if p[1] is not None]
    if len(valid) <= 2:
        return valid
    lo, hi = min(valid, key=lambda p: p[1]), max(valid, key=lambda p: p[1])
    return sorted({lo, hi}, key=lambda p: p[0])


def _break_gaps(pts):
    """A None between points further apart in x than ten median steps (at least 1.5 s): a line
    does not bridge a stretch without data."""
    steps = sorted(b[0] - a[0] for a, b in zip(pts, pts[1:]) if b[0] > a[0])
    if not steps:
        return pts
    limit = max(1.5, 10 * steps[len(steps) // 2])
    out = pts[:1]
    for a, b in zip(pts, pts[1:]):
        if b[0] - a[0] > limit:
            out.append((None, None))
        out.append(b)
    return out


def _polyline(frame, pts, color, width=1.4, step=False):
    """One <path> per run of points without None."""
    out, run = [], []
    for x, y in _break_gaps(list(pts)) + [(None, None)]:
        if x is None or y is None or not math.isfinite(y):
            if run:
                d = "M" + " L".join(
                    f"{frame.px(a):.1f},{frame.py(b):.1f}" for a, b in _steps(run, step)
                )
                out.append(f'<path d="{d}" fill="none" stroke="{color}" stroke-width="{width}"/>')
            run = []
        else:
            run.append((x, y))
    return out


def _steps(run, step):
    if not step:
        return run
    out = [run[0]]
    for (x0, y0), (x1, y1) in zip(run, run[1:]):
        out += [(x1, y0), (x1, y1)]
    return out


def text(x, y, content, anchor="start", bold=False):
    """An SVG <text> at (x, y) px, content escaped."""
    weight = ' font-weight="bold"' if bold else ""
    return f'<text x="{x:.1f}" y="{y:.1f}" text-anchor="{anchor}"{weight}>{escape(content)}</text>'


def line(x1, y1, x2, y2, stroke):
    return f'<line x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}" stroke="{stroke}"/>'


def plot_area(frame):
    """The white plot area, with its tick labels along x below it."""
    right, bottom = frame.width - frame.right, frame.height - frame.bottom
    out = [
        f'<rect x="{frame.left}" y="{frame.top}" width="{right - frame.left}" '
        f'height="{bottom - frame.top}" fill="#fff" stroke="#bbb"/>'
    ]
    for v in nice_ticks(frame.x0, frame.x1, 8):
        x = frame.px(v)
        out += [line(x, bottom, x, bottom + 4, "#888"), text(x, bottom + 15, _fmt(v), "middle")]
    return out


def _axes(frame, xlabel, ylabel, title=""):
    right = frame.width - frame.right
    out = plot_area(frame)
    for v in nice_ticks(frame.y0, frame.y1, 4):
        y = frame.py(v)
        out += [line(frame.left, y, right, y, "#eee"), text(frame.left - 4, y + 4, _fmt(v), "end")]
    out.append(text(right, frame.height - 3, xlabel, "end"))
    heading = f"{title} ({ylabel})" if title else ylabel
    out.append(text(12, frame.top - 8, heading, bold=True))
    return out


def _event_lines(frame, events):
    out = []
    for t, label, level in events:
        if t is None or not frame.x0 <= t <= frame.x1:
            continue
        x = frame.px(t)
        color = EVENT_COLOR.get(level, EVENT_COLOR["info"])
        out.append(
            f'<line x1="{x:.1f}" y1="{frame.top}" x2="{x:.1f}" y2="{frame.height - frame.bottom}" '
            f'stroke="{color}" stroke-dasharray="4,3"><title>{escape(label)}</title></line>'
        )
    return out


def _legend(series, width):
    out, x = [], width - PAD_R
    for i, s in reversed(list(enumerate(series))):
        label = escape(s["label"])
        x -= 14 + 6.5 * len(s["label"])
        color = s.get("color", COLORS[i % len(COLORS)])
        out.append(f'<rect x="{x:.0f}" y="6" width="10" height="10" fill="{color}"/>')
        out.append(f'<text x="{x + 13:.0f}" y="15">{label}</text>')
    return out


def _svg(width, height, body, title):
    return (
        f'<svg class="plot" viewBox="0 0 {width} {height}" '
        f'width="{width}" height="{height}" role="img" font-family="sans-serif" font-size="11">'
        f"<title>{escape(title)}</title>" + "".join(body) + "</svg>"
    )


def time_plot(series, title, ylabel, xlabel="s", x_range=None, events=(), floor_zero=True):
    """series: [{"label", "points": [(x, y)], "color"?, "step"?, "marker"?}]; events:
    [(x, label, level)] drawn as dashed vertical lines."""
    xs = [p[0] for s in series for p in s["points"]]
    x_range = x_range or _range(xs, pad=0.0)
    ys = [p[1] for s in series for p in s["points"] if x_range[0] <= p[0] <= x_range[1]]
    frame = Frame(x_range, _range(ys, floor_zero=floor_zero), W, H, (PAD_L, PAD_R, PAD_T, PAD_B))
    body = _axes(frame, xlabel, ylabel, title) + _event_lines(frame, events)
    x0, x1 = x_range
    for i, s in enumerate(series):
        color = s.get("color", COLORS[i % len(COLORS)])
        inside = [(x, y) for x, y in s["points"] if x0 <= x <= x1]  # inside the frame
        s = dict(s, points=decimate(sorted(inside, key=lambda p: p[0])))
        if s.get("marker"):
            body += [
                f'<circle cx="{frame.px(x):.1f}" cy="{frame.py(y):.1f}" r="2.5" fill="{color}"/>'
                for x, y in s["points"]
                if y is not None
            ]
        else:
            body += _polyline(frame, s["points"], color, step=s.get("step", False))
    return _svg(W, H, body + _legend(series, W), title)
