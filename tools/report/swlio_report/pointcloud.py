"""The merged map cloud (`swlio-run --map-pcd`, estimator/src/map/map_pcd.cpp): PCD with FIELDS
x y z, float32, DATA binary (ascii read too). Only a subsample of x, y is kept for the top view.
"""
import os
import struct

MAX_POINTS = 4000  # drawn under the trajectory: enough to see the yard, small in SVG


def _header(f):
    fields = {}
    while True:
        line = f.readline()
        if not line:
            return None
        key, _, value = line.decode("ascii", errors="replace").strip().partition(" ")
        if key and not key.startswith("#"):
            fields[key.upper()] = value.split()
        if key.upper() == "DATA":
            return fields


def _layout(fields):
    """(x index, y index, record size, struct format) of float32 fields, or None."""
    names = fields.get("FIELDS", [])
    sizes = [int(s) for s in fields.get("SIZE", [])]
    types = fields.get("TYPE", [])
    if "x" not in names or "y" not in names or len(sizes) != len(names) or len(types) != len(names):
        return None
    if any(t != "F" or s != 4 for t, s in zip(types, sizes)):
        return None
    return names.index("x"), names.index("y"), 4 * len(names), "<" + "f" * len(names)


def _binary(f, count, layout, max_points):
    ix, iy, size, fmt = layout
    data = f.read(count * size)
    count = min(count, len(data) // size)
    step = max(1, count // max_points)
    points = []
    for i in range(0, count, step):
        values = struct.unpack_from(fmt, data, i * size)
        points.append((values[ix], values[iy]))
    return points, count


def _ascii(f, layout, max_points):
    ix, iy = layout[0], layout[1]
    rows = []
    for line in f.read().decode("ascii", errors="replace").splitlines():
        parts = line.split()
        try:
            rows.append((float(parts[ix]), float(parts[iy])))
        except (ValueError, IndexError):
            continue
    step = max(1, len(rows) // max_points)
    return rows[::step], len(rows)


def read_xy(path, notes, max_points=MAX_POINTS):
    """Subsampled (x, y) of the cloud and its point count; ([], 0) with a note when unusable."""
    if not os.path.isfile(path):
        return [], 0
    with open(path, "rb") as f:
        fields = _header(f)
        layout = _layout(fields) if fields else None
        if layout is None:
            notes.append(f"{os.path.basename(path)}: not a PCD of float x y z")
            return [], 0
        count = int((fields.get("POINTS") or ["0"])[0])
        if fields["DATA"][:1] == ["binary"]:
            return _binary(f, count, layout, max_points)
        if fields["DATA"][:1] == ["ascii"]:
            return _ascii(f, layout, max_points)
    notes.append(f"{os.path.basename(path)}: DATA {fields['DATA']} not read")
    return [], 0
