#!/usr/bin/python3
"""scripts/lint's helper: a per-source compilation database, and the sources a change touches.

Usage: lint_select.py BUILD DB_OUT [CHANGED_LIST OURS_LIST]
  Writes DB_OUT/compile_commands.json from BUILD's, with every unity batch
  (**/Unity/unity_N_cxx.cxx, which includes several sources by their paths relative to it)
  replaced by one entry per member source with the batch's command (a batch holds one
  target's sources). With the two lists (newline-separated paths relative to the repository
  root), prints the sources of OURS_LIST to lint: those changed themselves, and those whose
  compilation reads a changed file, from `ninja -t deps`. A batch's dependency list does not
  say which member read a header, so those members are preprocessed on their own (`-MM`) to
  find out.
"""
import concurrent.futures
import json
import os
import re
import shlex
import subprocess
import sys


def expand(entries):
    out = []
    for e in entries:
        if "/Unity/unity_" not in e["file"]:
            out.append(e)
            continue
        with open(e["file"], encoding="utf-8") as f:
            members = re.findall(r'^#include "(.+)"$', f.read(), re.M)
        # cmake/SwlioUnity.cmake names members relative to the batch.
        members = [os.path.normpath(os.path.join(os.path.dirname(e["file"]), m)) for m in members]
        for m in members:
            out.append(dict(e, file=m, command=e["command"].replace(e["file"], m)))
    return out


def ninja_deps(build):
    """Every object's dependency list from ninja (its source first), as absolute paths: ninja
    stores them as the compiler wrote them, relative to the build directory when ccache's
    CCACHE_BASEDIR rewrote the include paths (scripts/ccache-env), else absolute."""
    text = subprocess.run(["ninja", "-C", build, "-t", "deps"], capture_output=True,
                          text=True, check=False).stdout
    blocks, deps = [], []
    for line in text.splitlines():
        if not line.startswith(" "):
            if deps:
                blocks.append(deps)
            deps = []
        elif line.strip():
            deps.append(os.path.normpath(os.path.join(os.path.abspath(build), line.strip())))
    if deps:
        blocks.append(deps)
    return blocks


def reads(entry):
    """Every file the compilation of `entry` reads (preprocessor only)."""
    args = shlex.split(entry["command"])
    keep, skip = [], False
    for a in args:
        if skip:
            skip = False
        elif a in ("-o", "-c", "-MF", "-MT"):
            skip = True
        elif a != "-MD":
            keep.append(a)
    keep += ["-MM", entry["file"]]
    text = subprocess.run(keep, cwd=entry["directory"], capture_output=True, text=True,
                          check=False).stdout
    return {os.path.normpath(os.path.join(entry["directory"], t))
            for t in text.replace("\\\n", " ").split()[1:]}


def select(build, entries, changed, ours):
    by_file = {e["file"]: e for e in entries}
    hit = set()
    to_check = []  # (member of a batch, the changed headers its batch read)
    for deps in ninja_deps(build):
        members = [d for d in deps if d in ours]
        changed_headers = {d for d in deps if d in changed and d not in ours}
        hit.update(d for d in deps if d in changed and d in ours)
        if not changed_headers:
            continue
        if len(members) <= 1:
            hit.update(members)
            continue
        to_check += [(m, changed_headers) for m in members if m in by_file]
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count()) as pool:
        found = pool.map(lambda c: reads(by_file[c[0]]) & c[1], to_check)
        hit.update(m for (m, _), read in zip(to_check, found) if read)
    return hit


def main():
    build, db_out = sys.argv[1], sys.argv[2]
    with open(os.path.join(build, "compile_commands.json"), encoding="utf-8") as f:
        entries = expand(json.load(f))
    os.makedirs(db_out, exist_ok=True)
    with open(os.path.join(db_out, "compile_commands.json"), "w", encoding="utf-8") as f:
        json.dump(entries, f, indent=0)
    if len(sys.argv) < 5:
        return
    root = os.getcwd() + "/"
    changed = {root + c for c in sys.argv[3].split("\n") if c}
    ours = {root + c for c in sys.argv[4].split("\n") if c}
    for path in sorted(select(build, entries, changed, ours)):
        print(path[len(root):])


if __name__ == "__main__":
    main()
