"""Tolerant readers of the CSV and TUM files the daemon and swlio-run write.

Every reader returns what it could read and appends a note (one line, the file's name first) to
`notes` for what it could not: a missing file, a truncated last line, garbage rows. Nothing
here raises on bad content.
"""
import math
import os


class Table:
    """Columns of a CSV file with a header line; numbers as float, anything else as str."""

    def __init__(self, header, rows):
        self.header = header
        self.columns = {name: [row[i] for row in rows] for i, name in enumerate(header)}
        self.rows = len(rows)

    def has(self, name):
        return name in self.columns

    def col(self, name):
        """The column's values, or a list of None when the file has no such column."""
        return self.columns.get(name, [None] * self.rows)

    def numbers(self, name):
        """The column with text turned into None (a gauge or counter)."""
        return [v if isinstance(v, float) else None for v in self.col(name)]


def _value(text):
    text = text.strip()
    try:
        number = float(text)
    except ValueError:
        return text
    return number if math.isfinite(number) else text  # nan, inf: not a usable number


def _describe_bad(name, bad):
    lines = ", ".join(str(n) for n in bad[:3]) + (" ..." if len(bad) > 3 else "")
    return f"{name}: {len(bad)} malformed line(s) skipped (line {lines})"


def read_csv(path, notes, required=("t_ns",)):
    """A CSV file with a header line, or None (with a note) when absent or unusable.

    Rows whose field count differs from the header's, or whose first column is not a number,
    are skipped and counted in one note.
    """
    name = os.path.basename(path)
    if not os.path.isfile(path):
        return None
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            lines = f.read().splitlines()
    except OSError as e:
        notes.append(f"{name}: cannot read ({e.strerror})")
        return None
    if not lines:
        notes.append(f"{name}: empty")
        return None
    header = [h.strip() for h in lines[0].split(",")]
    missing = [c for c in required if c not in header]
    if missing:
        notes.append(f"{name}: no header with {', '.join(missing)} (first line: {lines[0][:60]!r})")
        return None
    rows, bad = [], []
    for n, line in enumerate(lines[1:], start=2):
        if not line.strip():
            continue
        fields = [_value(v) for v in line.split(",")]
        if len(fields) != len(header) or not isinstance(fields[0], float):
            bad.append(n)
            continue
        rows.append(fields)
    if bad:
        notes.append(_describe_bad(name, bad))
    return Table(header, rows)


def read_tum(path, notes):
    """TUM trajectory rows (t_s, x, y, z), or None when absent."""
    name = os.path.basename(path)
    if not os.path.isfile(path):
        return None
    poses, bad = [], []
    with open(path, encoding="utf-8", errors="replace") as f:
        for n, line in enumerate(f, start=1):
            if not line.strip() or line.startswith("#"):
                continue
            try:
                values = [float(v) for v in line.split()]
            except ValueError:
                values = []
            if len(values) != 8 or not all(math.isfinite(v) for v in values):
                bad.append(n)
                continue
            poses.append(tuple(values[:4]))
    if bad:
        notes.append(_describe_bad(name, bad))
    if not poses:
        notes.append(f"{name}: no poses")
    return poses


def read_text(path, notes, limit_bytes=2_000_000):
    """A text file (at most limit_bytes of it), or None when absent."""
    if not os.path.isfile(path):
        return None
    with open(path, "rb") as f:
        data = f.read(limit_bytes + 1)
    if len(data) > limit_bytes:
        notes.append(f"{os.path.basename(path)}: longer than {limit_bytes} bytes; cut")
        data = data[:limit_bytes]
    return data.decode("utf-8", errors="replace")
