"""What the report reads: the kind of PATH and every file of it that exists.

PATH is an incident folder (a recording plus health.csv, log.txt, odometry.tum, config.yaml and
incident.yaml: docs/blackbox.md), a recording folder (lidar.pcap, imu.xbus,
imu.rx.csv, manifest.yaml; the black-box files may be absent) or the daemon's log directory
(swliod.log, swliod.1.log, ...).
"""
import os

from . import incident as incident_mod
from . import logs
from .tables import read_csv, read_text, read_tum

RECORDING_FILES = ("lidar.pcap", "imu.xbus", "imu.rx.csv", "manifest.yaml")
BLACKBOX_FILES = ("health.csv", "log.txt", "odometry.tum", "config.yaml")


class Inputs:
    """Everything read from PATH; absent parts are None (lists empty)."""

    def __init__(self, path, kind):
        self.path, self.kind = path, kind
        self.notes = []  # one line per problem with the input
        self.present = {}  # file name -> size in bytes
        self.health = None  # tables.Table of health.csv
        self.log_lines = []  # logs.LogLine, time order
        self.odometry = None  # [(t_s, x, y, z)] of odometry.tum
        self.config_text = None
        self.manifest_text = None
        self.incident = None  # incident.Incident
        self.clock_offsets = None


def detect_kind(path):
    """'incident', 'recording', 'logdir' or None (with the reason) for anything else."""
    if not os.path.isdir(path):
        return None, f"{path} is not a directory"
    names = set(os.listdir(path))
    if "incident.yaml" in names:
        return "incident", ""
    if names & set(RECORDING_FILES + BLACKBOX_FILES):
        return "recording", ""
    if logs.log_files(path):
        return "logdir", ""
    return None, (
        f"{path} holds no recording ({', '.join(RECORDING_FILES)}), no incident.yaml "
        "and no swliod log files"
    )


def _size(path):
    try:
        return os.path.getsize(path)
    except OSError:
        return None


def _read_folder(inputs):
    p, notes = inputs.path, inputs.notes
    for name in (
        RECORDING_FILES + BLACKBOX_FILES + ("incident.yaml", "can.log", "clock_offsets.csv")
    ):
        size = _size(os.path.join(p, name))
        if size is not None:
            inputs.present[name] = size
    inputs.health = read_csv(os.path.join(p, "health.csv"), notes, required=("t_ns",))
    inputs.odometry = read_tum(os.path.join(p, "odometry.tum"), notes)
    inputs.config_text = read_text(os.path.join(p, "config.yaml"), notes)
    inputs.manifest_text = read_text(os.path.join(p, "manifest.yaml"), notes)
    inputs.clock_offsets = read_csv(
        os.path.join(p, "clock_offsets.csv"), notes, required=("t_monotonic_ns",)
    )
    text = read_text(os.path.join(p, "log.txt"), notes)
    if text is not None:
        inputs.log_lines = logs.parse_lines(text, "log.txt", notes)
    if inputs.kind == "incident":
        inputs.incident = incident_mod.read(os.path.join(p, "incident.yaml"), notes)


def _read_logdir(inputs):
    lines = []
    for path in logs.log_files(inputs.path):
        name = os.path.basename(path)
        inputs.present[name] = _size(path)
        text = read_text(path, inputs.notes, limit_bytes=50_000_000)
        lines += logs.parse_lines(text or "", name, inputs.notes)
    lines.sort(key=lambda line: line.utc_s)  # stable: a file's own order within a millisecond
    inputs.log_lines = lines


def read(path):
    """Inputs of PATH; raises ValueError (with the reason) only when PATH is none of the kinds."""
    kind, reason = detect_kind(path)
    if kind is None:
        raise ValueError(reason)
    inputs = Inputs(os.path.abspath(path), kind)
    if kind == "logdir":
        _read_logdir(inputs)
    else:
        _read_folder(inputs)
    return inputs
