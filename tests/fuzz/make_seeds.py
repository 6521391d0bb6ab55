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


# --- seeds for rosbag2_fuzz: the real .db3 bags, trimmed, and one synthetic bag -------------
# (make_bag_seeds, a C++ program, writes the MCAP, ROS 1 and message seeds.)
import shutil
import sqlite3
import tempfile

# CDR packet-array element sizes (research/bags.md §2.2-2.4): Time + payload, 4-aligned.
ELEMENT_BYTES = {"rslidar_msg/msg/RslidarScan": 1256, "velodyne_msgs/msg/VelodyneScan": 1216,
                 "robosense_msgs/msg/RobosenseScan": 1516}


def trim_scan(blob, element, keep=3):
    """A packet-array message (CDR_LE) cut to its first `keep` packets, count patched."""
    name_len = struct.unpack_from("<I", blob, 12)[0]
    at = (16 + name_len + 3) // 4 * 4
    return blob[:at] + struct.pack("<I", keep) + blob[at + 4:at + 4 + keep * element]


def small_db3(src, dst, per_topic=2):
    """Copy of `src` with the first `per_topic` messages of each topic, scans trimmed, 512 B pages."""
    tmp = tempfile.mkdtemp()
    work = os.path.join(tmp, "bag.db3")
    shutil.copyfile(src, work)
    db = sqlite3.connect(work)
    types = dict(db.execute("SELECT id, type FROM topics"))
    keep = []
    for tid in types:
        keep += [r[0] for r in db.execute(
            "SELECT id FROM messages WHERE topic_id=? ORDER BY timestamp LIMIT ?", (tid, per_topic))]
    db.execute("DELETE FROM messages WHERE id NOT IN (%s)" % ",".join(map(str, keep)))
    for mid, tid, blob in db.execute("SELECT id, topic_id, data FROM messages").fetchall():
        if types[tid] in ELEMENT_BYTES:
            db.execute("UPDATE messages SET data=? WHERE id=?", (trim_scan(blob, ELEMENT_BYTES[types[tid]]), mid))
    db.commit()
    db.execute("PRAGMA page_size=512")
    db.execute("VACUUM")
    db.close()
    shutil.copyfile(work, dst)
    shutil.rmtree(tmp)


def synthetic_db3(dst):
    """A schema-3 bag with an IMU topic (three CDR sensor_msgs/Imu) and a topic of another type."""
    if os.path.exists(dst):
        os.remove(dst)
    db = sqlite3.connect(dst)
    db.execute("PRAGMA page_size=512")
    db.execute("CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL)")
    db.execute("INSERT INTO schema VALUES(3, 'humble')")
    db.execute("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
               "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL)")
    db.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
               "timestamp INTEGER NOT NULL, data BLOB NOT NULL)")
    db.execute("CREATE INDEX timestamp_idx ON messages (timestamp ASC)")
    db.execute("INSERT INTO topics VALUES(1, '/imu/data', 'sensor_msgs/msg/Imu', 'cdr', '')")
    db.execute("INSERT INTO topics VALUES(2, '/chatter', 'std_msgs/msg/String', 'cdr', '')")
    for k in range(3):
        # CDR_LE; stamp; frame "imu_link" (9 with NUL) + 3 pad; 4+9+3+9+3+9 = 37 float64 fields.
        imu = b"\x00\x01\x00\x00" + struct.pack("<iI", 1700000000, 10000000 * k)
        imu += struct.pack("<I", 9) + b"imu_link\x00" + b"\x00" * 3
        imu += struct.pack("<37d", *([0.0] * 3 + [1.0] + [0.0] * 9 + [0.01, 0.0, 0.0] + [0.0] * 9
                                      + [0.0, 0.0, 9.81] + [0.0] * 9))
        db.execute("INSERT INTO messages(topic_id, timestamp, data) VALUES(1, ?, ?)",
                   (1700000000000000000 + 10000000 * k + 500, imu))
    db.execute("INSERT INTO messages(topic_id, timestamp, data) VALUES(2, 1700000000000000001, ?)",
               (b"\x00\x01\x00\x00\x03\x00\x00\x00hi\x00",))
    db.commit()
    db.close()


os.makedirs(os.path.join(out_dir, "rosbag2"), exist_ok=True)
for name, rel in [("rs16", "rs16_washing_house/rosbag2_2022_08_16-11_55_30_0.db3"),
                  ("vlp16", "velodyne_nebula/vlp16/1673400471837873222_0.db3"),
                  ("vlp32", "velodyne_nebula/vlp32/1713492677464078412_0.db3"),
                  ("helios16p", "rs_helios16p_nebula/rosbag2_2023_08_03-11_02_46_0.db3")]:
    small_db3(os.path.join(data_dir, rel), os.path.join(out_dir, "rosbag2", name + ".db3"))
synthetic_db3(os.path.join(out_dir, "rosbag2", "synthetic.db3"))
print("seeds for rosbag2 in", out_dir)
