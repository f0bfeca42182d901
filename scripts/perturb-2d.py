#!/usr/bin/env python3
"""Make another laser out of a 2D KITTI-style folder, to try the defaults on data they were not tuned on.

A 2D log converted to a KITTI folder (velodyne/NNNNNN.bin of float32 x, y, z, intensity; poses.txt;
optional times.txt), such as the corrected CARMEN logs, is written again as if another laser had
recorded the same walk:

  --every-other-beam     half the beams (a 361-beam scanner becomes a 181-beam one)
  --max-range R          returns beyond R metres dropped (e.g. 5.6 for a Hokuyo URG-04LX)
  --range-noise SIGMA    Gaussian range noise of SIGMA metres along each beam (seeded: same output each time)
  --every-nth-scan N     every Nth scan only (key frames N times further apart); poses and times follow

The poses (the reference) are kept, so `revisit run OUT` reports the odometry's and the closures'
accuracy against them. Nothing is written outside OUT, and OUT must not exist yet.

  scripts/perturb-2d.py ../shared/data/carmen_kitti/seattle /tmp/seattle-181 --every-other-beam
  revisit run /tmp/seattle-181 --out /tmp/run-seattle-181
"""
import argparse
import os
import sys

import numpy as np


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("source", help="KITTI-style 2D folder (velodyne/, poses.txt)")
    parser.add_argument("out", help="new folder to write (must not exist)")
    parser.add_argument("--every-other-beam", action="store_true")
    parser.add_argument("--max-range", type=float, default=0.0)
    parser.add_argument("--range-noise", type=float, default=0.0)
    parser.add_argument("--every-nth-scan", type=int, default=1)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()

    scans_dir = os.path.join(args.source, "velodyne")
    names = sorted(n for n in os.listdir(scans_dir) if n.endswith(".bin"))
    poses = np.loadtxt(os.path.join(args.source, "poses.txt"), ndmin=2)
    if len(poses) != len(names):
        sys.exit(f"{args.source}: {len(names)} scans but {len(poses)} poses")
    times_file = os.path.join(args.source, "times.txt")
    times = np.loadtxt(times_file, ndmin=1) if os.path.exists(times_file) else None
    if args.every_nth_scan < 1:
        sys.exit("--every-nth-scan must be >= 1")
    if os.path.lexists(args.out):
        sys.exit(f"{args.out}: exists; give a new folder")
    for name in names:  # checked before anything is written
        size = os.path.getsize(os.path.join(scans_dir, name))
        if size % 16 != 0:
            sys.exit(f"{os.path.join(scans_dir, name)}: {size} bytes, not whole points of 4 float32 (x, y, z, intensity)")

    os.makedirs(os.path.join(args.out, "velodyne"))
    rng = np.random.default_rng(args.seed)
    kept = list(range(0, len(names), args.every_nth_scan))
    for index, k in enumerate(kept):
        points = np.fromfile(os.path.join(scans_dir, names[k]), dtype=np.float32).reshape(-1, 4)
        if args.every_other_beam:
            points = points[::2]
        ranges = np.linalg.norm(points[:, :2], axis=1)
        if args.max_range > 0.0:
            points, ranges = points[ranges <= args.max_range], ranges[ranges <= args.max_range]
        if args.range_noise > 0.0:
            scale = 1.0 + rng.normal(0.0, args.range_noise, size=len(points)) / np.maximum(ranges, 1e-6)
            points = points.copy()
            points[:, :2] *= scale[:, None]
        points.astype(np.float32).tofile(os.path.join(args.out, "velodyne", f"{index:06d}.bin"))
    np.savetxt(os.path.join(args.out, "poses.txt"), poses[kept], fmt="%.9f")
    if times is not None:
        np.savetxt(os.path.join(args.out, "times.txt"), times[kept], fmt="%.6f")
    print(f"wrote {len(kept)} scans to {args.out}")


if __name__ == "__main__":
    main()
