"""The page's sections after the summary: figures, logs around events, configuration, notes."""
from html import escape

from . import figures as fig
from . import trajectory
from .html_page import absent

LOG_WINDOW_S = 10.0  # log lines this far either side of an event
MAX_EVENTS_WITH_LOGS = 20  # events whose log lines are shown
MAX_LINES_PER_EVENT = 80


def _figures(title, anchor, svgs, missing):
    shown = [s for s in svgs if s]
    body = "".join(shown) if shown else absent(missing)
    return f'<section id="{anchor}"><h2>{escape(title)}</h2>{body}</section>'


def trajectory_section(ctx):
    svg = trajectory.figure(ctx.inputs, ctx.replay, ctx.tl)
    replay = ctx.replay
    notes = []
    if ctx.inputs.odometry is None:
        notes.append("no odometry.tum (the daemon's published odometry) in this input")
    if replay is None:
        notes.append("no replay (--no-replay, or not a recording)")
    elif replay.error:
        notes.append(f"no replay: {replay.error}")
    elif not replay.map_points:
        notes.append("the replay wrote no map cloud")
    else:
        notes.append(
            f"map: {len(replay.map_points):,} points drawn for the {replay.map_total:,} of the "
            "replay's merged cloud (0.5 m cells whose points span ≥ 0.4 m in height)"
        )
    text = "".join(f"<p><small>{escape(n)}</small></p>" for n in notes)
    body = svg or absent("No trajectory: neither odometry.tum nor a replay.")
    return f'<section id="trajectory"><h2>Trajectory over the map</h2>{body}{text}</section>'


def figure_sections(ctx):
    f = fig.Figures(ctx)
    source = (
        f"<p><small>source: {escape(ctx.ev.source or 'raw recording files / replay')}</small></p>"
    )
    return [
        trajectory_section(ctx),
        _figures(
            "Sensors: rates and errors",
            "sensors",
            fig.sensor_rates(f) + [fig.sensor_errors(f)],
            "No sensor rates: no health.csv, no status lines, no raw recording files.",
        ).replace("</h2>", "</h2>" + source, 1),
        _figures(
            "Clocks: offset, drift, jumps",
            "clocks",
            fig.clock_plots(f),
            "No clock data: health.csv is absent (the replay's clock jumps are in the summary).",
        ),
        _figures(
            "Estimator: update time, iterations, degeneracy, covariance",
            "estimator",
            fig.estimator_plots(f),
            "No estimator data: no health.csv and no replay.",
        ),
        _figures(
            "Loop closures and relocalizations",
            "loops",
            fig.loop_plots(f) + [_loop_log(ctx)],
            "No loop-closure data: no health.csv and no replay with loops.",
        ),
        _figures(
            "CPU and queues",
            "system",
            fig.system_plots(f),
            "No CPU or queue data: health.csv and status lines are absent.",
        ),
    ]


def _line_html(line, tl, at=None):
    cls = line.level + (" at" if at is not None and abs(line.utc_s - at) < 0.5 else "")
    t = tl.utc(tl.host(line.utc_s)) if tl.utc_offset is not None else f"{line.utc_s:.3f}"
    return f'<div class="{cls}">{escape(t)} {escape(line.level)} {escape(line.message)}</div>'


def _loop_log(ctx):
    lines = [
        l
        for l in ctx.inputs.log_lines
        if any(k in l.message for k in ("loop closure", "relocaliz", "localization", "localized"))
    ]
    if not lines:
        return ""
    shown = "".join(_line_html(l, ctx.tl) for l in lines[:100])
    return (
        f"<details><summary>{len(lines)} log line(s) about loop closure and localization</summary>"
        f'<div class="log">{shown}</div></details>'
    )


def logs_section(ctx):
    tl, lines = ctx.tl, ctx.inputs.log_lines
    if not lines:
        return (
            '<section id="logs"><h2>Log lines around events</h2>'
            + absent("No log lines: no log.txt / swliod.log in this input.")
            + "</section>"
        )
    if tl.utc_offset is None or not tl.marks:
        problems = [l for l in lines if l.is_problem()][:200]
        body = "".join(_line_html(l, tl) for l in problems) or "<div>no warnings or errors</div>"
        return (
            f'<section id="logs"><h2>Warnings and errors</h2><div class="log">{body}</div>'
            f"{_all_lines(lines, tl)}</section>"
        )
    parts = []
    for m in tl.marks[:MAX_EVENTS_WITH_LOGS]:
        at = m.t + tl.utc_offset
        near = [l for l in lines if abs(l.utc_s - at) <= LOG_WINDOW_S][:MAX_LINES_PER_EVENT]
        body = (
            "".join(_line_html(l, tl, at) for l in near) or "<div>no log lines within ±10 s</div>"
        )
        parts.append(
            f"<h3>{escape(tl.utc(m.t))} {escape(m.label)}</h3>"
            f'<p><small>{escape(m.detail)}</small></p><div class="log">{body}</div>'
        )
    more = len(tl.marks) - MAX_EVENTS_WITH_LOGS
    if more > 0:
        parts.append(f"<p><small>{more} more event(s) not shown</small></p>")
    return (
        '<section id="logs"><h2>Log lines around events (±10 s)</h2>'
        + "".join(parts)
        + _all_lines(lines, tl)
        + "</section>"
    )


def _all_lines(lines, tl, limit=3000):
    shown = "".join(_line_html(l, tl) for l in lines[-limit:])
    cut = f" (the last {limit})" if len(lines) > limit else ""
    return (
        f"<details><summary>all {len(lines):,} log lines{cut}</summary>"
        f'<div class="log">{shown}</div></details>'
    )


def config_section(ctx):
    inputs, replay = ctx.inputs, ctx.replay
    parts = []
    for name, text in (
        ("config.yaml (the daemon's effective configuration)", inputs.config_text),
        ("manifest.yaml (the recording)", inputs.manifest_text),
    ):
        if text is not None:
            parts.append(
                f"<details><summary>{escape(name)}</summary><pre>{escape(text)}</pre></details>"
            )
    if replay is not None and (replay.command or replay.stderr_tail):
        parts.append(
            "<details><summary>the replay: swlio-run's command and last messages</summary>"
            "<pre>" + escape("\n".join([replay.command] + replay.stderr_tail)) + "</pre></details>"
        )
    body = "".join(parts) or absent("No config.yaml or manifest.yaml in this input.")
    return f'<section id="config"><h2>Configuration</h2>{body}</section>'


def notes_section(ctx):
    notes = ctx.inputs.notes + (["replay: " + n for n in ctx.replay.notes] if ctx.replay else [])
    body = (
        ("<ul>" + "".join(f'<li class="note">{escape(n)}</li>' for n in notes) + "</ul>")
        if notes
        else "<p>Every file present was read without problems.</p>"
    )
    return f'<section id="notes"><h2>Notes on the input</h2>{body}</section>'
