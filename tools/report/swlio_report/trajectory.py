"""Top view of the trajectories (the daemon's odometry.tum, the replay's) over the replay's map
cloud, with each event marked where the robot was at its time."""
import bisect

from .svg_map import top_view


def position_at(poses, t):
    """(x, y) on a TUM trajectory [(t, x, y, z)] at time t, interpolated; None outside it."""
    if not poses or t is None or t < poses[0][0] - 1.0 or t > poses[-1][0] + 1.0:
        return None
    times = [p[0] for p in poses]
    i = bisect.bisect_left(times, t)
    if i <= 0:
        return poses[0][1:3]
    if i >= len(poses):
        return poses[-1][1:3]
    (t0, x0, y0, _), (t1, x1, y1, _) = poses[i - 1], poses[i]
    a = (t - t0) / (t1 - t0) if t1 > t0 else 0.0
    return x0 + a * (x1 - x0), y0 + a * (y1 - y0)


def figure(inputs, replay, timeline):
    """The SVG, or None when there is no trajectory at all."""
    paths = []
    daemon = inputs.odometry or []
    replayed = replay.trajectory if replay and replay.trajectory else []
    if daemon:
        paths.append(
            {
                "label": "daemon odometry (odometry.tum)",
                "points": [p[1:3] for p in daemon],
                "color": "#1f77b4",
            }
        )
    if replayed:
        paths.append(
            {
                "label": "replay (swlio-run)",
                "points": [p[1:3] for p in replayed],
                "color": "#ff7f0e",
                "dashed": bool(daemon),
            }
        )
    if not paths:
        return None
    reference = daemon or replayed
    marks = []
    for m in timeline.marks:
        xy = position_at(reference, m.t)
        if xy is not None:
            marks.append((xy[0], xy[1], f"{timeline.utc(m.t)} {m.label}", m.level))
    cloud = replay.map_points if replay else []
    return top_view(
        paths, cloud, marks[:12], "Trajectory over the map, top view", _loop_links(replay, replayed)
    )


def _loop_links(replay, poses):
    """Both ends of every loop closure the replay accepted, on its trajectory."""
    loops = replay.loops if replay else None
    if loops is None or not poses:
        return []
    links = []
    for a, b, verdict in zip(
        loops.numbers("candidate_t_ns"), loops.numbers("node_t_ns"), loops.col("verdict")
    ):
        ends = [position_at(poses, t * 1e-9) if t is not None else None for t in (a, b)]
        if verdict == "accepted" and None not in ends:
            links.append(tuple(ends))
    return links
