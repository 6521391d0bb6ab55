"""Top view (x east/right, y north/up) of the map cloud, trajectories and marked events, equal
axes, as inline SVG."""
from html import escape

from .svg_plot import COLORS, EVENT_COLOR, Frame, _fmt, _svg, nice_ticks, plot_area, text

WIDTH, MIN_H, MAX_H = 880, 320, 760
PADS = (52, 14, 26, 30)


CLOUD_MARGIN_M = 25.0  # the map cloud is drawn this far around the trajectories, no further


def _bounds(paths, points):
    """The trajectories' extent plus a margin of the cloud around them (the cloud's alone when
    there is no trajectory)."""
    xs = [p[0] for path in paths for p in path["points"]]
    ys = [p[1] for path in paths for p in path["points"]]
    if xs:
        m = CLOUD_MARGIN_M
        box = (min(xs) - m, max(xs) + m, min(ys) - m, max(ys) + m)
        near = [p for p in points if box[0] <= p[0] <= box[1] and box[2] <= p[1] <= box[3]]
        xs, ys = xs + [p[0] for p in near], ys + [p[1] for p in near]
    else:
        xs, ys = [p[0] for p in points], [p[1] for p in points]
    if not xs:
        return (0.0, 1.0), (0.0, 1.0)
    return (min(xs), max(xs)), (min(ys), max(ys))


def _equal_frame(paths, points):
    (x0, x1), (y0, y1) = _bounds(paths, points)
    dx, dy = max(x1 - x0, 1.0), max(y1 - y0, 1.0)
    x0, x1, y0, y1 = x0 - 0.04 * dx, x1 + 0.04 * dx, y0 - 0.04 * dy, y1 + 0.04 * dy
    inner_w = WIDTH - PADS[0] - PADS[1]
    m_per_px = (x1 - x0) / inner_w
    inner_h = (y1 - y0) / m_per_px
    if inner_h > MAX_H - PADS[2] - PADS[3]:  # tall: keep the height, widen x around its centre
        inner_h = MAX_H - PADS[2] - PADS[3]
        m_per_px = (y1 - y0) / inner_h
        cx, half = (x0 + x1) / 2, inner_w * m_per_px / 2
        x0, x1 = cx - half, cx + half
    inner_h = max(inner_h, MIN_H - PADS[2] - PADS[3])
    cy, half = (y0 + y1) / 2, inner_h * m_per_px / 2
    height = int(inner_h + PADS[2] + PADS[3])
    return Frame((x0, x1), (cy - half, cy + half), WIDTH, height, PADS)


def _grid(frame):
    out = plot_area(frame)
    for v in nice_ticks(frame.y0, frame.y1, 6):
        y = frame.py(v)
        out.append(text(frame.left - 4, y + 4, _fmt(v), "end"))
    out.append(text(frame.width - frame.right, frame.height - 3, "x (m)", "end"))
    out.append(text(8, frame.top - 8, "y (m)"))
    return out


def _cloud(frame, points):
    if not points:
        return []
    d = "".join(f"M{frame.px(x):.1f} {frame.py(y):.1f}h0" for x, y in points)
    return [
        f'<path d="{d}" stroke="#9aa5b1" stroke-width="1.6" stroke-linecap="round" fill="none"/>'
    ]


def _path(frame, path, color):
    pts = path["points"]
    if len(pts) < 2:
        return []
    step = max(1, len(pts) // 3000)
    sampled = pts[::step] + [pts[-1]]
    d = "M" + " L".join(f"{frame.px(x):.1f},{frame.py(y):.1f}" for x, y in sampled)
    dash = ' stroke-dasharray="6,4"' if path.get("dashed") else ""
    return [
        f'<path d="{d}" fill="none" stroke="{color}" stroke-width="1.8"{dash}/>',
        f'<circle cx="{frame.px(pts[0][0]):.1f}" cy="{frame.py(pts[0][1]):.1f}" r="4" '
        f"fill=\"{color}\"><title>start of {escape(path['label'])}</title></circle>",
    ]


def _links(frame, links):
    """Thin green lines between the two ends of each accepted loop closure."""
    if not links:
        return []
    d = "".join(
        f"M{frame.px(a[0]):.1f},{frame.py(a[1]):.1f}L{frame.px(b[0]):.1f},{frame.py(b[1]):.1f}"
        for a, b in links
    )
    return [
        f'<path d="{d}" stroke="#27ae60" stroke-width="1.2" fill="none"><title>{len(links)} '
        f"accepted loop closure(s)</title></path>"
    ]


def _marks(frame, marks):
    out = []
    for i, (x, y, label, level) in enumerate(marks):
        color = EVENT_COLOR.get(level, EVENT_COLOR["info"])
        px, py = frame.px(x), frame.py(y)
        out.append(
            f'<circle cx="{px:.1f}" cy="{py:.1f}" r="6" fill="none" stroke="{color}" '
            f'stroke-width="2.5"><title>{escape(label)}</title></circle>'
        )
        right = px > frame.width * 0.6  # labels right of a mark near the right edge would be cut
        tx, anchor = (px - 8, "end") if right else (px + 8, "start")
        out.append(
            f'<text x="{tx:.1f}" y="{py - 6 - 11 * (i % 3):.1f}" fill="{color}" '
            f'text-anchor="{anchor}" font-weight="bold">{escape(label[:48])}</text>'
        )
    return out


def _legend(paths, has_cloud, has_links):
    items = [(p.get("color", COLORS[i % len(COLORS)]), p["label"]) for i, p in enumerate(paths)]
    if has_links:
        items.append(("#27ae60", "loop closures (replay)"))
    if has_cloud:
        items.append(("#9aa5b1", "map: what stands up (replay's cloud)"))
    out, x = [], PADS[0]
    for color, label in items:
        out.append(f'<rect x="{x}" y="6" width="10" height="10" fill="{color}"/>')
        out.append(f'<text x="{x + 13}" y="15">{escape(label)}</text>')
        x += 24 + int(6.5 * len(label))
    return out


def top_view(paths, cloud, marks, title, links=()):
    """paths: [{"label", "points": [(x, y)], "color"?, "dashed"?}]; cloud: [(x, y)];
    marks: [(x, y, label, level)]; links: [((x, y), (x, y))]."""
    frame = _equal_frame(paths, cloud)
    inside = [p for p in cloud if frame.x0 <= p[0] <= frame.x1 and frame.y0 <= p[1] <= frame.y1]
    body = _grid(frame) + _cloud(frame, inside)
    for i, path in enumerate(paths):
        body += _path(frame, path, path.get("color", COLORS[i % len(COLORS)]))
    body += _links(frame, links) + _marks(frame, marks) + _legend(paths, bool(cloud), bool(links))
    return _svg(WIDTH, frame.height, body, title)
