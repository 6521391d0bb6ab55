#!/usr/bin/env python3
"""Seed corpora for rs16_fuzz and pcap_fuzz from the real RS-LiDAR-16 capture.

Usage: python3 tests/fuzz/make_seeds.py [DATA_DIR] [OUT_DIR]
  DATA_DIR defaults to ../shared/data, OUT_DIR to build-fuzz/seeds.
Writes OUT_DIR/rs16/* (an option byte, then one DIFOP and consecutive MSOP payloads, several
windows of the capture including an azimuth wrap) and OUT_DIR/pcap/* (the capture's global
header plus its first records, and a version cut inside a record).
Then e.g.: build-fuzz/bin/rs16_fuzz -max_total_time=60 build-fuzz/corpus/rs16 OUT_DIR/rs16
"""
import os
import struct
import sys

data_dir = sys.argv[1] if len(sys.argv) > 1 else "../shared/data"
out_dir = sys.argv[2] if len(sys.argv) > 2 else "build-fuzz/seeds"
path = os.path.join(data_dir, "rs16_washing_house", "rs16_msop2244_difop7788.repackaged.pcap")
raw = open(path, "rb").read()

records = []  # (record bytes incl. header, udp payload)
off = 24
while off + 16 <= len(raw):
    incl = struct.unpack("<I", raw[off + 8:off + 12])[0]
    rec = raw[off:off + 16 + incl]
    records.append((rec, rec[16 + 42:]))
    off += 16 + incl

msop = [p for _, p in records if p[:2] == b"\x55\xaa"]
difop = [p for _, p in records if p[:2] == b"\xa5\xff"]
os.makedirs(os.path.join(out_dir, "rs16"), exist_ok=True)
os.makedirs(os.path.join(out_dir, "pcap"), exist_ok=True)
for i, (start, option) in enumerate([(0, 0x00), (70, 0x01), (700, 0x02), (1500, 0x85), (2990, 0x40)]):
    seed = bytes([option]) + difop[0] + b"".join(msop[start:start + 8])
    open(os.path.join(out_dir, "rs16", "seed%d" % i), "wb").write(seed)
for n in (1, 3, 6):
    blob = raw[:24] + b"".join(r for r, _ in records[:n])
    open(os.path.join(out_dir, "pcap", "first%d" % n), "wb").write(blob)
open(os.path.join(out_dir, "pcap", "cut"), "wb").write(raw[:24] + records[0][0] + records[1][0][:700])
print("seeds in", out_dir)


# --- seeds for the other decoders (added for scripts/fuzz) ---------------------------------
def udp_payloads(pcap_path):
    """UDP payloads of a classic pcap with Ethernet/IPv4/UDP records (our repackaged captures)."""
    data = open(pcap_path, "rb").read()
    out, pos = [], 24
    while pos + 16 <= len(data):
        incl = struct.unpack("<I", data[pos + 8:pos + 12])[0]
        out.append(data[pos + 16 + 42:pos + 16 + incl])
        pos += 16 + incl
    return out


def write_seeds(name, blobs):
    os.makedirs(os.path.join(out_dir, name), exist_ok=True)
    for i, blob in enumerate(blobs):
        open(os.path.join(out_dir, name, "seed%d" % i), "wb").write(blob)


helios = udp_payloads(os.path.join(data_dir, "rs_helios16p_nebula",
                                   "helios16p_msop6699_difop7788.repackaged.pcap"))
write_seeds("helios16p", [p for p in helios if len(p) == 1248][::75][:12])
vlp = udp_payloads(os.path.join(data_dir, "velodyne_nebula", "vlp16", "vlp16_port2368.repackaged.pcap"))
write_seeds("vlp16", vlp[::60][:12])
xbus = [open(os.path.join(data_dir, "xsens_einride_mti-g-710", str(k), "output.bin"), "rb").read()[:3000]
        for k in range(1, 6)]
xbus.append(open(os.path.join(data_dir, "xsens_scottapotamas_mti-300", "test_frames_mti-300.bin"), "rb").read())
write_seeds("xbus", xbus)
write_seeds("can", [b"\x00(1700000000.123456) can0 201#0A0B0C0D00000000",
                    b"\x02(1700000000.5) can1 18FF0101#R5",
                    b"\x01" + bytes(range(12)) + struct.pack("<IBB", 0x201, 0, 8) + bytes(8)])
print("seeds for helios16p, vlp16, xbus, can in", out_dir)
