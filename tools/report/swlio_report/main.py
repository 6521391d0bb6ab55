"""swlio-report PATH [-o OUT.html]: wires inputs, replay, verdicts and sections into one page."""
import argparse
import os
import sys
import tempfile
import time

from . import evidence, html_page, inputs as inputs_mod, raw_sensors, replay as replay_mod
from . import sections, timeline, verdicts


def parse_args(argv):
    p = argparse.ArgumentParser(
        prog="swlio-report",
        description="One self-contained HTML page that says what happened: an incident folder, a "
        "recording folder or the daemon's log directory (docs/report.md).",
    )
    p.add_argument("path", help="incident folder, recording folder or swliod log directory")
    p.add_argument("-o", "--out", help="the HTML file (default: <PATH's name>.report.html here)")
    p.add_argument("--no-replay", action="store_true", help="do not run swlio-run on the recording")
    p.add_argument(
        "--swlio-run", help="the swlio-run program (default: beside this script, then PATH)"
    )
    p.add_argument(
        "--keep-replay", metavar="DIR", help="write swlio-run's outputs here and keep them"
    )
    return p.parse_args(argv)


def _replay(args, inputs, script_dir):
    if args.no_replay or inputs.kind == "logdir" or "lidar.pcap" not in inputs.present:
        return None
    program = replay_mod.find_swlio_run(args.swlio_run, script_dir)
    config = os.path.join(inputs.path, "config.yaml") if inputs.config_text is not None else None
    mb = inputs.present["lidar.pcap"] / 1e6
    print(
        f"swlio-report: replaying {mb:.0f} MB of LiDAR with swlio-run (--no-replay skips it; "
        "about 6 s per 100 MB on a quiet core)",
        file=sys.stderr,
    )
    if args.keep_replay:
        os.makedirs(args.keep_replay, exist_ok=True)
        return replay_mod.run(program, inputs.path, args.keep_replay, config)
    with tempfile.TemporaryDirectory(prefix="swlio-report-") as out:
        return replay_mod.run(program, inputs.path, out, config)


def _raw(inputs):
    if inputs.kind == "logdir" or inputs.health is not None:
        return None
    return raw_sensors.read(inputs.path, inputs.notes)


def build_page(inputs, replay):
    """The HTML text for what was read (and replayed)."""
    raw = _raw(inputs)
    tl = timeline.build(inputs, replay, raw)
    ev = evidence.build(inputs, tl)
    ctx = verdicts.Context(inputs, ev, tl, replay, raw)
    judged = verdicts.judge(ctx)
    name = os.path.basename(inputs.path.rstrip("/")) or inputs.path
    body = [html_page.summary(inputs, tl, replay, judged)] + sections.figure_sections(ctx)
    body += [sections.logs_section(ctx), sections.config_section(ctx), sections.notes_section(ctx)]
    return html_page.page(f"swlio report: {name}", body)


def main(argv=None, script_dir=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    script_dir = script_dir or os.path.dirname(os.path.abspath(sys.argv[0]))
    try:
        inputs = inputs_mod.read(args.path)
    except ValueError as e:
        print(f"swlio-report: {e}", file=sys.stderr)
        return 2
    start = time.monotonic()
    replay = _replay(args, inputs, script_dir)
    replay_s = time.monotonic() - start
    html = build_page(inputs, replay)
    out = args.out or os.path.basename(os.path.abspath(args.path)) + ".report.html"
    try:
        with open(out, "w", encoding="utf-8") as f:
            f.write(html)
    except OSError as e:
        print(f"swlio-report: cannot write {out}: {e.strerror}", file=sys.stderr)
        return 1
    page_s = time.monotonic() - start - replay_s
    print(
        f"swlio-report: {out} ({len(html.encode()) / 1024:.0f} KB; replay {replay_s:.1f} s, "
        f"page {page_s:.1f} s)"
    )
    return 0
