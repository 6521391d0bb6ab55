"""Receive times straight from a recording's raw files, for recordings without health.csv:
lidar.pcap's record headers (record time = host receive time) and imu.rx.csv
(`byte_offset,bytes,t_rx_ns`, one row per serial burst).
"""
import os
import struct

from .tables import read_csv

_PCAP_MAGIC = {
    b"\xd4\xc3\xb2\xa1": ("<", 1e-6),
    b"\xa1\xb2\xc3\xd4": (">", 1e-6),
    b"\x4d\x3c\xb2\xa1": ("<", 1e-9),
    b"\xa1\xb2\x3c\x4d": (">", 1e-9),
}


def pcap_times(path, notes):
    """Receive time (s) of every packet in the pcap, or None when absent or not a pcap."""
    if not os.path.isfile(path):
        return None
    times = []
    with open(path, "rb") as f:
        magic = f.read(24)[:4]
        if magic not in _PCAP_MAGIC:
            notes.append("lidar.pcap: not a pcap file (magic " + magic.hex() + ")")
            return None
        order, unit = _PCAP_MAGIC[magic]
        header = struct.Struct(order + "IIII")
        while True:
            raw = f.read(16)
            if len(raw) < 16:
                if raw:
                    notes.append("lidar.pcap: truncated after %d packets" % len(times))
                break
            sec, frac, incl, _ = header.unpack(raw)
            times.append(sec + frac * unit)
            f.seek(incl, os.SEEK_CUR)
    return times


def imu_bursts(path, notes):
    """[(receive time s, bytes)] of imu.rx.csv, or None."""
    table = read_csv(path, notes, required=("t_rx_ns", "bytes"))
    if table is None:
        return None
    return [
        (t * 1e-9, b)
        for t, b in zip(table.numbers("t_rx_ns"), table.numbers("bytes"))
        if t is not None and b is not None
    ]


def per_second(times, weights=None):
    """[(bin centre s, count or sum of weights per second)] in whole 1 s bins."""
    if not times:
        return []
    t0 = min(times)
    bins = {}
    for i, t in enumerate(times):
        k = int(t - t0)
        bins[k] = bins.get(k, 0.0) + (weights[i] if weights else 1.0)
    last = max(bins)  # the last second is partial: left out
    return [(t0 + k + 0.5, bins.get(k, 0.0)) for k in range(last)]


class RawSensors:
    def __init__(self):
        self.lidar_times = None  # packet receive times (s)
        self.imu = None  # [(t, bytes)]


def read(folder, notes):
    raw = RawSensors()
    raw.lidar_times = pcap_times(os.path.join(folder, "lidar.pcap"), notes)
    raw.imu = imu_bursts(os.path.join(folder, "imu.rx.csv"), notes)
    return raw
