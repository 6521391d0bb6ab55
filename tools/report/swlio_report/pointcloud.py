"""The merged map cloud (`swlio-run --map-pcd`, estimator/src/map/map_pcd.cpp): PCD with FIELDS
x y z, float32, DATA binary (ascii read too), reduced for the top view to what stands up: the
centres of the grid cells whose points span at least STRUCTURE_M in height (walls, fences, poles,
equipment; the ground drops out), at most MAX_POINTS of them. A cloud with too few such cells
(a flat one, or one without z) is drawn as an even subsample instead.
"""
import os
import struct

MAX_POINTS = 5000  # drawn under the trajectory: enough to see the yard, small in SVG
CELL_M = 0.5  # grid cell of the top view
STRUCTURE_M = 0.4  # a cell whose points span this much height holds something standing
MIN_CELLS = 200  # fewer standing cells than this: an even subsample of the points instead


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
    """(x, y, z index (z: None when absent), record size, struct format) of float32 fields."""
    names = fields.get("FIELDS", [])
    try:
        sizes = [int(s) for s in fields.get("SIZE", [])]
    except ValueError:
        return None
    types = fields.get("TYPE", [])
    if "x" not in names or "y" not in names or len(sizes) != len(names) or len(types) != len(names):
        return None
    if any(t != "F" or s != 4 for t, s in zip(types, sizes)):
        return None
    iz = names.index("z") if "z" in names else None
    return names.index("x"), names.index("y"), iz, 4 * len(names), "<" + "f" * len(names)


def _binary(f, count, layout):
    ix, iy, iz, size, fmt = layout
    data = f.read(count * size)
    count = min(count, len(data) // size)
    return [
        (v[ix], v[iy], v[iz] if iz is not None else 0.0)
        for v in struct.iter_unpack(fmt, data[: count * size])
    ]


def _ascii(f, layout):
    ix, iy, iz = layout[0], layout[1], layout[2]
    rows = []
    for line in f.read().decode("ascii", errors="replace").splitlines():
        parts = line.split()
        try:
            rows.append(
                (float(parts[ix]), float(parts[iy]), float(parts[iz]) if iz is not None else 0.0)
            )
        except (ValueError, IndexError):
            continue
    return rows


def standing(points, max_points=MAX_POINTS):
    """Centres of the cells whose points span STRUCTURE_M in height, else an even subsample."""
    cells = {}
    for x, y, z in points:
        if x != x or y != y or z != z:  # NaN
            continue
        key = (int(x // CELL_M), int(y // CELL_M))
        lo, hi = cells.get(key, (z, z))
        cells[key] = (min(lo, z), max(hi, z))
    tall = [(kx, ky) for (kx, ky), (lo, hi) in cells.items() if hi - lo >= STRUCTURE_M]
    if len(tall) < MIN_CELLS:
        step = max(1, -(-len(points) // max_points))
        return [(x, y) for x, y, _ in points[::step]]
    tall.sort()
    step = max(1, -(-len(tall) // max_points))
    return [((kx + 0.5) * CELL_M, (ky + 0.5) * CELL_M) for kx, ky in tall[::step]]


def read_xy(path, notes, max_points=MAX_POINTS):
    """(x, y) to draw (see standing()) and the cloud's point count; ([], 0) with a note when
    unusable."""
    if not os.path.isfile(path):
        return [], 0
    with open(path, "rb") as f:
        fields = _header(f)
        layout = _layout(fields) if fields else None
        if layout is None:
            notes.append(f"{os.path.basename(path)}: not a PCD of float x y z")
            return [], 0
        count = (
            int((fields.get("POINTS") or ["0"])[0])
            if (fields.get("POINTS") or ["x"])[0].isdigit()
            else 0
        )
        if fields["DATA"][:1] == ["binary"]:
            points = _binary(f, count, layout)
            return standing(points, max_points), len(points)
        if fields["DATA"][:1] == ["ascii"]:
            points = _ascii(f, layout)
            return standing(points, max_points), len(points)
    notes.append(f"{os.path.basename(path)}: DATA {fields['DATA']} not read")
    return [], 0
