"""Readers of the run folder's text files, written from docs/formats.md (not through the module)."""
import csv

import numpy as np


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def pose(row, prefix):
    T = np.eye(4)
    for r in range(3):
        for c in range(4):
            T[r, c] = float(row[f"{prefix}_{r}{c}"])
    return T


def accepted_closures(run):
    """closures.csv rows the pose graph used: accepted, by the detector or the proximity pass."""
    return [row for row in read_csv(run / "closures.csv")
            if row["accepted"] == "1" and row["method"] in ("density", "proximity")]


def read_kitti_poses(path):
    rows = np.loadtxt(path, ndmin=2)
    poses = np.tile(np.eye(4), (len(rows), 1, 1))
    poses[:, :3, :] = rows.reshape(-1, 3, 4)
    return poses
