"""The page shell and its summary: title, what the input is, span, the incident, verdicts.

Self-contained: styles inline, no scripts, no fonts, no external references.
"""
from html import escape

from .verdicts import THRESHOLDS

CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:0 auto;max-width:920px;
padding:12px 18px;color:#222;background:#fafafa;font-size:14px}
h1{font-size:21px;margin:6px 0}h2{font-size:17px;margin:22px 0 6px;border-bottom:1px solid #ccc}
h3{font-size:14px;margin:12px 0 4px}
table{border-collapse:collapse;width:100%;margin:4px 0}td,th{padding:3px 6px;text-align:left;
vertical-align:top;border-bottom:1px solid #e3e3e3}th{background:#eee}
.badge{display:inline-block;min-width:66px;text-align:center;border-radius:3px;color:#fff;
font-weight:bold;padding:1px 4px}.ok{background:#27ae60}.degraded{background:#d68910}
.failed{background:#c0392b}.nodata{background:#95a5a6}
.absent{color:#777;font-style:italic}.note{color:#a04000}
pre{background:#fff;border:1px solid #ddd;padding:6px;overflow-x:auto;font-size:12px;margin:4px 0}
.log{font-family:monospace;font-size:12px;white-space:pre-wrap;word-break:break-all}
.log .warn{background:#fdebd0}.log .error,.log .critical{background:#f5b7b1}
.log .at{font-weight:bold;border-left:3px solid #c0392b}
svg.plot{display:block;max-width:100%;height:auto;margin:4px 0}
small{color:#666}
.headline{font-size:15px;margin:6px 0 10px;padding-left:0;list-style:none}.headline li{margin:3px 0}
"""

KIND_TEXT = {
    "incident": "an incident kept by the black box",
    "recording": "a recording folder",
    "logdir": "the daemon's log directory",
}


def badge(level):
    cls = level if level in ("ok", "degraded", "failed") else "nodata"
    return f'<span class="badge {cls}">{escape(level)}</span>'


def absent(text):
    return f'<p class="absent">{escape(text)}</p>'


def _facts(inputs, timeline, replay):
    utc = (
        ""
        if timeline.utc_offset is not None
        else ("; UTC unknown: no health.csv, incident.yaml or realtime offset in the manifest")
    )
    rows = [
        ("input", f"{KIND_TEXT[inputs.kind]}: {inputs.path}"),
        (
            "span (UTC)",
            f"{timeline.utc_full(timeline.start)} → {timeline.utc_full(timeline.end)} "
            f"({timeline.end - timeline.start:.1f} s{utc})",
        ),
    ]
    inc = inputs.incident
    if inc is not None:
        rows.append(
            (
                "incident",
                f"{inc.reason} at {inc.opened_utc or '?'}"
                + (f" (swlio {inc.version})" if inc.version else ""),
            )
        )
    if replay is not None:
        rows.append(
            (
                "replay",
                f"{replay.error}"
                if replay.error
                else f"swlio-run in {replay.seconds:.1f} s (command under Configuration)",
            )
        )
    files = ", ".join(
        f"{n} ({s / 1024:.0f} KB)" for n, s in sorted(inputs.present.items()) if s is not None
    )
    rows.append(("files", files or "none"))
    return (
        "<table>"
        + "".join(f"<tr><th>{escape(k)}</th><td>{escape(v)}</td></tr>" for k, v in rows)
        + "</table>"
    )


def _events(inputs, timeline):
    inc = inputs.incident
    if inc is None or not inc.events:
        return ""
    rows = "".join(
        f"<tr><td>{escape(e.utc or timeline.utc(e.t_ns * 1e-9 if e.t_ns else None))}</td>"
        f"<td>{escape(e.reason)}</td><td>{escape(e.detail)}</td></tr>"
        for e in inc.events
    )
    head = "<tr><th>UTC</th><th>reason</th><th>detail</th></tr>"
    return f"<h3>Incident events</h3><table>{head}{rows}</table>"


def _verdicts(verdicts):
    rows = "".join(
        f"<tr><td>{escape(v.subsystem)}</td><td>{badge(v.label())}</td>"
        f"<td>{escape(v.reason())}</td></tr>"
        for v in verdicts
    )
    rules = "".join(f"<li><b>{escape(n)}</b>: {escape(t)}</li>" for n, t in THRESHOLDS)
    return (
        "<h3>Verdict per subsystem</h3><table>"
        "<tr><th>subsystem</th><th>verdict</th><th>why</th></tr>"
        f"{rows}</table><details><summary>thresholds</summary><ul>{rules}</ul></details>"
    )


def headline(verdicts):
    """One sentence: the failed and degraded subsystems with their first reason, or all ok."""
    bad = [v for v in verdicts if v.level in ("failed", "degraded")]
    bad.sort(key=lambda v: v.level != "failed")
    if not bad:
        judged = [v.subsystem for v in verdicts if v.level == "ok"]
        return f'<p class="headline">All judged subsystems ok ({", ".join(judged) or "none"}).</p>'
    parts = "".join(
        f"<li>{badge(v.level)} <b>{escape(v.subsystem)}</b>: "
        f"{escape(v.reason().split('; ')[0])}</li>"
        for v in bad
    )
    return f'<ul class="headline">{parts}</ul>'


def summary(inputs, timeline, replay, verdicts):
    return (
        '<section id="summary"><h2>Summary</h2>'
        + headline(verdicts)
        + _facts(inputs, timeline, replay)
        + _verdicts(verdicts)
        + _events(inputs, timeline)
        + "</section>"
    )


def page(title, sections):
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        f'<meta name="viewport" content="width=device-width"><title>{escape(title)}</title>'
        f"<style>{CSS}</style></head><body><h1>{escape(title)}</h1>"
        + "".join(sections)
        + "</body></html>\n"
    )
