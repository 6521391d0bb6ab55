"""incident.yaml (docs/blackbox.md): why the black box kept this span.

```
format: swlio-incident 1
swlio_version: "<version> (<git describe>)"
reason: <first event's reason>
t_event_ns: <daemon host ns>
opened_utc: "2026-12-04T14:32:07.120Z"
span: {start_ns: .., end_ns: .., start_utc: "..", end_utc: "..", cut_short: false}
events:
  - {t_ns: .., utc: "..", reason: lidar_silent, detail: "no LiDAR datagram for 1.0 s"}
```
"""
import os

try:
    import yaml
except ImportError:  # python3-yaml is in scripts/install-deps; without it: a note
    yaml = None


class Event:
    def __init__(self, t_ns, utc, reason, detail):
        self.t_ns, self.utc, self.reason, self.detail = t_ns, utc, reason, detail


class Incident:
    def __init__(self):
        self.format = self.version = self.reason = self.opened_utc = None
        self.t_event_ns = None
        self.span = {}
        self.events = []


def _int(value):
    try:
        return int(value)
    except (TypeError, ValueError):
        return None


def _event(entry):
    if not isinstance(entry, dict):
        return None
    return Event(
        _int(entry.get("t_ns")),
        str(entry.get("utc", "")),
        str(entry.get("reason", "unknown")),
        str(entry.get("detail", "")),
    )


def from_mapping(doc, notes):
    """An Incident from the parsed YAML mapping; what does not fit the spec gets a note."""
    inc = Incident()
    inc.format = doc.get("format")
    if inc.format != "swlio-incident 1":
        notes.append(f"incident.yaml: format {inc.format!r}, expected 'swlio-incident 1'")
    inc.version = doc.get("swlio_version")
    inc.reason = str(doc.get("reason", "unknown"))
    inc.t_event_ns = _int(doc.get("t_event_ns"))
    inc.opened_utc = doc.get("opened_utc")
    span = doc.get("span")
    inc.span = span if isinstance(span, dict) else {}
    events = doc.get("events") or []
    if not isinstance(events, list):
        notes.append("incident.yaml: events is not a list")
        events = []
    inc.events = [e for e in (_event(x) for x in events) if e is not None]
    if len(inc.events) != len(events):
        notes.append(f"incident.yaml: {len(events) - len(inc.events)} malformed event(s) skipped")
    return inc


def read(path, notes):
    """The incident, or None with a note when the file is absent or unreadable."""
    if not os.path.isfile(path):
        return None
    if yaml is None:
        notes.append("incident.yaml: python3-yaml is not installed; not read")
        return None
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            doc = yaml.safe_load(f)
    except yaml.YAMLError as e:
        notes.append(f"incident.yaml: not YAML ({str(e).splitlines()[0]})")
        return None
    if not isinstance(doc, dict):
        notes.append("incident.yaml: not a mapping")
        return None
    return from_mapping(doc, notes)
