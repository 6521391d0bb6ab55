#!/usr/bin/env python3
"""Counts a saved map's points on simulated actors (issue 36).

    scripts/map_movers.py RECORDING MAP EST_TUM [--margin-m 0.15]

RECORDING is a swlio-sim output with actors.csv (--disturb people,vehicles); MAP a saved map
(swlio-run --loop-closure on --save-map MAP, estimator/map-format.md); EST_TUM the same run's
--out trajectory, which puts the map frame into the simulator's world: at each node's time
the transform that takes the estimated pose onto the true one (groundtruth.tum), so that only
the local pose error counts, not the drift far from there. A map point counts as on an actor when it lies in that actor's box
(grown by --margin-m sideways and on top, not below: the ground it stands on is not the actor)
at the time of the keyframe that stored it (actors.csv is at 10 Hz: the nearest row). Prints
the points on moving actors (moves = 1), on actors parked all drive, and the total.
"""
import argparse
import bisect
import math
import struct
import sys
from collections import defaultdict


def read_map(path):
    data = open(path, "rb").read()
    if data[:8] != b"SWLIOMAP":
        sys.exit(f"{path}: not a saved map")
    _, _, rings, sectors = struct.unpack_from("<4I", data, 8)
    (count,) = struct.unpack_from("<I", data, 48)
    off, nodes = 52, []
    for _ in range(count):
        t_ns = struct.unpack_from("<q", data, off)[0]
        pose = struct.unpack_from("<14d", data, off + 8)
        n_planes, n_edges = struct.unpack_from("<2I", data, off + 120)
        n = n_planes + n_edges
        flat = struct.unpack_from(f"<{3 * n}f", data, off + 128)
        off += 128 + 12 * n + 4 * rings * sectors
        nodes.append((t_ns, Pose(pose[:7]), Pose(pose[7:]),
                      [flat[3 * i:3 * i + 3] for i in range(n)]))
    return nodes


class Pose:
    """x y z qx qy qz qw → rotation matrix and translation."""

    def __init__(self, p):
        x, y, z, w = p[3:7]
        q = math.sqrt(x * x + y * y + z * z + w * w)
        x, y, z, w = x / q, y / q, z / q, w / q
        self.R = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
        self.t = list(p[:3])

    @staticmethod
    def of(R, t):
        p = Pose([0, 0, 0, 0, 0, 0, 1])
        p.R, p.t = R, t
        return p

    def __mul__(self, o):
        R = [[sum(self.R[i][k] * o.R[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
        return Pose.of(R, self.apply(o.t))

    def inverse(self):
        Rt = [[self.R[j][i] for j in range(3)] for i in range(3)]
        return Pose.of(Rt, [-sum(Rt[i][k] * self.t[k] for k in range(3)) for i in range(3)])

    def apply(self, p):
        return [sum(self.R[i][k] * p[k] for k in range(3)) + self.t[i] for i in range(3)]


def read_tum(path):
    rows = [l.split() for l in open(path) if l.strip() and not l.startswith("#")]
    return [round(float(r[0]) * 1e9) for r in rows], [Pose([float(v) for v in r[1:8]]) for r in rows]


def nearest(times, t):
    k = bisect.bisect_left(times, t)
    return min((j for j in (k - 1, k) if 0 <= j < len(times)), key=lambda j: abs(times[j] - t))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("recording")
    ap.add_argument("map")
    ap.add_argument("est")
    ap.add_argument("--margin-m", type=float, default=0.15)
    a = ap.parse_args()

    t_gt, p_gt = read_tum(f"{a.recording}/groundtruth.tum")
    t_est, p_est = read_tum(a.est)

    actors = defaultdict(list)  # t_ns → [(moves, centre, yaw, half)]
    for line in open(f"{a.recording}/actors.csv").readlines()[1:]:
        f = line.strip().split(",")
        actors[int(f[0])].append((int(f[3]), [float(v) for v in f[4:7]], float(f[7]),
                                  [float(v) for v in f[8:11]]))
    times = sorted(actors)

    total = on_moving = on_parked = 0
    # Node times are the recording's host time (ns), as groundtruth.tum's and actors.csv's.
    for t_ns, T_map_imu, T_imu_lidar, pts in read_map(a.map):
        T_world_map = p_gt[nearest(t_gt, t_ns)] * p_est[nearest(t_est, t_ns)].inverse()
        T = T_world_map * T_map_imu * T_imu_lidar
        boxes = actors[times[nearest(times, t_ns)]] if times else []
        for p in pts:
            w = T.apply(p)
            total += 1
            for moves, c, yaw, half in boxes:
                d = [w[i] - c[i] for i in range(3)]
                lx = math.cos(yaw) * d[0] + math.sin(yaw) * d[1]
                ly = -math.sin(yaw) * d[0] + math.cos(yaw) * d[1]
                if (abs(lx) <= half[0] + a.margin_m and abs(ly) <= half[1] + a.margin_m and
                        -half[2] + 0.05 <= d[2] <= half[2] + a.margin_m):
                    if moves:
                        on_moving += 1
                    else:
                        on_parked += 1
                    break
    print(f"map points {total}, on moving actors {on_moving} ({100.0 * on_moving / max(total, 1):.2f} %), "
          f"on parked-all-drive actors {on_parked}")


if __name__ == "__main__":
    main()
