"""Verdict rules for the estimator, loop closure / localization, CPU and queues, and the black
box itself (thresholds in verdicts.py)."""
from . import series
from .inputs import BLACKBOX_FILES
from .verdicts import (
    HEALTH_GAP_S,
    QUEUE_DROPS,
    QUEUE_FILL,
    REINITIALIZATIONS,
    SKIPPED_BEHIND,
    UPDATE_MS,
    _events,
    count,
)


def _first_state(ctx, states, wanted):
    for t, s in zip(*states):
        if s in wanted and t is not None:
            return t, s
    return None, None


def _replay_estimator(v, ctx):
    summary = ctx.replay.summary if ctx.replay else {}
    if not summary:
        return
    reinit, failed = summary.get("reinitializations", 0), summary.get("match_failed", 0)
    if reinit:
        v.add("failed", f"replay: {reinit} re-initialization(s)")
    if failed:
        v.add("degraded", f"replay: {failed} sweeps whose match failed")
    v.add(
        "ok",
        f"replay: {summary.get('tracked', 0)} of {summary.get('scans', 0)} sweeps tracked, "
        f"mean {summary.get('mean_scan_ms', 0):.1f} ms",
    )


def _reinitializations(v, ctx):
    """Re-initializations after a divergence fail; an operator's resets are only said."""
    ev = ctx.ev
    if ev.has("estimator_divergences"):
        reinit = ev.grew("estimator_divergences")
        first = series.first_increase(*ev.get("estimator_divergences"))
        if reinit > REINITIALIZATIONS:
            v.add("failed", f"{count(reinit)} re-initialization(s), first at {ctx.tl.utc(first)}")
        else:
            v.add("ok", "no re-initialization")
    resets = ev.grew("estimator_operator_resets")
    if resets > 0:
        first = series.first_increase(*ev.get("estimator_operator_resets"))
        v.add("ok", f"{count(resets)} operator reset(s), first at {ctx.tl.utc(first)}")


def estimator(v, ctx):
    ev = ctx.ev
    _reinitializations(v, ctx)
    t, state = _first_state(ctx, ev.states, ("lost",))
    if t is not None:
        v.add("failed", f"tracking lost at {ctx.tl.utc(t)}")
    t, state = _first_state(ctx, ev.states, ("degraded",))
    if t is not None:
        v.add("degraded", f"state degraded from {ctx.tl.utc(t)}")
    worst = ev.maximum("estimator_max_update_ms")
    if worst is not None and worst > UPDATE_MS:
        v.add("degraded", f"a sweep's update took {worst:.0f} ms (> {UPDATE_MS:g} ms)")
    _events(v, ctx, ("divergence",), "failed")
    _replay_estimator(v, ctx)


def _loop_counts(v, ctx):
    ev = ctx.ev
    if ev.has("loop_accepted"):
        accepted, rejected = ev.grew("loop_accepted"), ev.grew("loop_rejected")
        corr = ev.maximum("loop_correction_m")
        corr_text = f", correction up to {corr:.2f} m" if corr is not None else ""
        v.add("ok", f"{count(accepted)} loops accepted, {count(rejected)} rejected{corr_text}")
    loops = ctx.replay.loops if ctx.replay else None
    if loops is not None:
        verdicts = loops.col("verdict")
        v.add(
            "ok", f"replay: {verdicts.count('accepted')} of {loops.rows} loop candidates accepted"
        )


def localization(v, ctx):
    ev = ctx.ev
    lost = ev.grew("loc_lost")
    if lost > 0:
        first = series.first_increase(*ev.get("loc_lost"))
        v.add("failed", f"localization lost {count(lost)} time(s), first at {ctx.tl.utc(first)}")
    t, state = _first_state(ctx, ev.loc_states, ("lost",))
    if t is not None and lost == 0:
        v.add("failed", f"localization state lost at {ctx.tl.utc(t)}")
    t, state = _first_state(ctx, ev.loc_states, ("ambiguous",))
    if t is not None:
        v.add("degraded", f"localization ambiguous at {ctx.tl.utc(t)}")
    used = any(s for s in ev.loc_states[1]) or ev.grew("loc_tracked") > 0
    if used and lost == 0:
        v.add("ok", f"localization: {count(ev.grew('loc_tracked'))} sweeps tracked in the map")
    _events(v, ctx, ("localization_lost",), "failed")
    _events(v, ctx, ("localization_ambiguous",), "degraded")
    for line in ctx.logged("localization: lost")[:1]:
        v.add("failed", "log: " + line.message[:80])
    _loop_counts(v, ctx)


def cpu_percent(ev):
    """[(t, CPU % of one core)] from the cumulative cpu_s column."""
    return [(t, 100.0 * r) for t, r in series.rate(*ev.get("cpu_s"))] if ev.has("cpu_s") else []


def cpu_queues(v, ctx):
    ev = ctx.ev
    for name, limit, what in (
        ("estimator_skipped_behind", SKIPPED_BEHIND, "sweeps skipped behind"),
        ("queue_dropped", QUEUE_DROPS, "queue drops"),
    ):
        if ev.has(name):
            n = ev.grew(name)
            v.add("degraded" if n > limit else "ok", f"{count(n)} {what}")
    fill = ev.maximum("queue_max_fill")
    if fill is not None:
        v.add("degraded" if fill > QUEUE_FILL else "ok", f"fullest queue {fill:.0%}")
    cpu = [c for _, c in cpu_percent(ev)]
    if cpu:
        v.add("ok", f"CPU mean {sum(cpu) / len(cpu):.0f} %, max {max(cpu):.0f} % of a core")
    _events(v, ctx, ("estimator_behind", "queue_drops"), "degraded")
    _events(v, ctx, ("watchdog",), "failed")
    for line in ctx.logged("degraded: CPU")[:1]:
        v.add("degraded", "log: " + line.message[:80])


def black_box(v, ctx):
    inputs = ctx.inputs
    has_box = inputs.kind == "incident" or "health.csv" in inputs.present
    if not has_box:  # a plain recording or a log directory: no black box to judge
        v.missing = "not a black-box incident (no health.csv, incident.yaml)"
        return
    absent = [f for f in BLACKBOX_FILES if f not in inputs.present]
    if absent:
        v.add("degraded", "absent: " + ", ".join(absent))
    if inputs.incident is not None and inputs.incident.span.get("cut_short"):
        v.add("degraded", "span cut short (incident.yaml)")
    ts = series.seconds(inputs.health.numbers("t_ns")) if inputs.health else []
    holes = series.gaps(ts, HEALTH_GAP_S)
    if holes:
        v.add(
            "degraded",
            f"{len(holes)} hole(s) in health.csv, longest {max(h[1] for h in holes):.1f} s",
        )
    if inputs.notes:
        v.add("degraded", f"{len(inputs.notes)} problem(s) reading the files (see Notes)")
    span = ctx.tl.end - ctx.tl.start
    v.add(
        "ok",
        f"{span:.0f} s kept: {count(len(ts))} health rows, "
        f"{count(len(inputs.log_lines))} log lines",
    )
