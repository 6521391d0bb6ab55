#!/usr/bin/python3
"""APE of a drive localized in a saved map, without aligning it to its ground truth.

Usage: scripts/localization_eval.py MAP_EST.tum MAP_GT.tum EST.tum GT.tum [--json]

The saved map's frame is the mapping drive's odometry frame (its first pose graph node). The
one transform from it to the simulator's world comes from the mapping drive alone: its
optimized trajectory (MAP_EST, from swlio-run --out-optimized) aligned to its ground truth
(MAP_GT) by an SE(3) Umeyama fit. The localized drive (EST: swlio-run --map --localize --out)
is then put into the world with that transform and compared with its own ground truth (GT)
as it is: a wrong relocalization or a drifting track shows in full.
"""
import json
import sys

import numpy as np


def read_tum(path):
    rows = [l.split() for l in open(path) if l.strip() and not l.startswith("#")]
    return np.array(rows, dtype=float)


def associate(est, gt, max_dt=0.01):
    """Pairs (est index, gt index) with the nearest ground-truth stamp within max_dt."""
    k = np.clip(np.searchsorted(gt[:, 0], est[:, 0]), 1, len(gt) - 1)
    prev = np.abs(gt[k - 1, 0] - est[:, 0]) < np.abs(gt[k, 0] - est[:, 0])
    k = np.where(prev, k - 1, k)
    ok = np.abs(gt[k, 0] - est[:, 0]) <= max_dt
    return np.nonzero(ok)[0], k[ok]


def umeyama_se3(src, dst):
    """R, t minimizing sum |dst - (R src + t)|² (Umeyama 1991, no scale)."""
    mu_s, mu_d = src.mean(0), dst.mean(0)
    cov = (dst - mu_d).T @ (src - mu_s) / len(src)
    u, _, vt = np.linalg.svd(cov)
    s = np.eye(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        s[2, 2] = -1
    r = u @ s @ vt
    return r, mu_d - r @ mu_s


def main(argv):
    if len(argv) < 5:
        print(__doc__)
        return 2
    map_est, map_gt, est, gt = (read_tum(p) for p in argv[1:5])
    i, j = associate(map_est, map_gt)
    r, t = umeyama_se3(map_est[i, 1:4], map_gt[j, 1:4])
    i, j = associate(est, gt)
    if len(i) == 0:
        print("no localized pose matches the ground truth's stamps")
        return 1
    p = est[i, 1:4] @ r.T + t
    err = np.linalg.norm(p - gt[j, 1:4], axis=1)
    # For comparison with APE figures elsewhere: the localized drive aligned to its own ground
    # truth (SE(3) Umeyama), which hides a local offset of the map.
    r2, t2 = umeyama_se3(est[i, 1:4], gt[j, 1:4])
    err_se3 = np.linalg.norm(est[i, 1:4] @ r2.T + t2 - gt[j, 1:4], axis=1)
    out = {"poses": int(len(i)), "ape_rmse_m": float(np.sqrt(np.mean(err ** 2))),
           "ape_rmse_m_own_se3": float(np.sqrt(np.mean(err_se3 ** 2))),
           "ape_mean_m": float(err.mean()), "ape_max_m": float(err.max()),
           "first_localized_s_after_gt_start": float(est[i[0], 0] - gt[0, 0]),
           "map_alignment_rmse_m": float(np.sqrt(np.mean(np.sum(
               (map_est[associate(map_est, map_gt)[0], 1:4] @ r.T + t
                - map_gt[associate(map_est, map_gt)[1], 1:4]) ** 2, axis=1))))}
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
