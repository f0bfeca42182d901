#!/usr/bin/env python3
"""Per-scan overhead of driving ClosurePipeline from Python, against the C++ calls it makes.

The KITTI scans of ../shared/data/kitti00_first16 are loaded once into numpy, then fed LAPS times with
their reference poses, each lap moved on by the lap's travel so that local maps close and the detector
runs as on a long drive. The C++ time is measured around each C++ ClosurePipeline::AddScan call inside the module
(timings()["add_scan"]): what a C++ loop over the same scans spends. The Python time is the wall time
of the add_scan calls: the call, the array view, the GIL and the result's conversion on top.

Usage: bench/python_overhead.py [--data DIR] [--laps N] [--repeats R] [--svg FILE.svg]
Run with PYTHONPATH=build/python and Debian's /usr/bin/python3."""
import argparse
import os
import sys
import time

import numpy as np

import revisit


def load(folder):
    dataset = revisit.open_dataset(folder)
    scans = [(np.ascontiguousarray(s.points), s.T_world_sensor) for s in dataset]
    if not scans or scans[0][1] is None:
        sys.exit(f"{folder}: needs scans with reference poses (poses.txt)")
    return scans


def laps_of(scans, laps):
    """The scans repeated, each lap's poses moved by the travel of the laps before it."""
    first, last = scans[0][1], scans[-1][1]
    # Maps the first scan's pose one scan step past the last one: each lap continues where the last ended.
    step = last @ np.linalg.inv(scans[-2][1]) @ last @ np.linalg.inv(first)
    offset = np.eye(4)
    for _ in range(laps):
        for points, pose in scans:
            yield points, offset @ pose
        offset = offset @ step


def measure(scans, laps):
    pipeline = revisit.ClosurePipeline(revisit.load_config())
    wall = 0.0
    count = 0
    for points, pose in laps_of(scans, laps):
        start = time.perf_counter()
        pipeline.add_scan(points, T_world_sensor=pose)
        wall += time.perf_counter() - start
        count += 1
    inside_ms = pipeline.timings()["add_scan"][0]
    return count, wall * 1e3, inside_ms, pipeline.num_maps


def write_svg(path, cpp_ms, python_ms, count):
    """Two bars, ms per scan: the C++ calls and the Python calls around them."""
    top = max(cpp_ms, python_ms) * 1.15
    height, width, bar = 220, 360, 90
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height + 70}" font-family="sans-serif">',
             f'<text x="{width / 2}" y="18" text-anchor="middle" font-size="13">{count} KITTI scans per run: '
             f'overhead {100 * (python_ms / cpp_ms - 1):.1f}%</text>']
    for i, (label, value, color) in enumerate([("C++ AddScan", cpp_ms, "#4c72b0"), ("add_scan from Python", python_ms, "#dd8452")]):
        h = height * value / top
        x = 60 + i * (bar + 60)
        parts.append(f'<rect x="{x}" y="{30 + height - h:.1f}" width="{bar}" height="{h:.1f}" fill="{color}"/>')
        parts.append(f'<text x="{x + bar / 2}" y="{25 + height - h:.1f}" text-anchor="middle" font-size="12">{value:.3f} ms</text>')
        parts.append(f'<text x="{x + bar / 2}" y="{height + 48}" text-anchor="middle" font-size="12">{label}</text>')
    parts.append(f'<line x1="40" y1="{30 + height}" x2="{width - 20}" y2="{30 + height}" stroke="black"/>')
    parts.append(f'<text x="12" y="{30 + height / 2}" font-size="12" transform="rotate(-90 12 {30 + height / 2})" '
                 f'text-anchor="middle">ms per scan</text></svg>')
    with open(path, "w") as f:
        f.write("\n".join(parts) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data", "kitti00_first16"))
    parser.add_argument("--laps", type=int, default=40)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--svg", help="write a bar chart of the per-scan times (SVG)")
    args = parser.parse_args()
    if not os.path.isdir(args.data):
        print(f"skipped: {args.data} is missing (the shared KITTI scans)")
        return 77
    scans = load(args.data)
    rows = []
    for repeat in range(args.repeats):
        count, python_ms, cpp_ms, maps = measure(scans, args.laps)
        rows.append((python_ms / count, cpp_ms / count))
        print(f"run {repeat + 1}: {count} scans, {maps} maps: Python {python_ms / count:.3f} ms/scan, "
              f"C++ AddScan {cpp_ms / count:.3f} ms/scan, overhead {100 * (python_ms / cpp_ms - 1):.1f}%")
    python_ms, cpp_ms = np.median(np.array(rows), axis=0)
    print(f"median: Python {python_ms:.3f} ms/scan, C++ {cpp_ms:.3f} ms/scan, overhead "
          f"{python_ms - cpp_ms:.3f} ms/scan = {100 * (python_ms / cpp_ms - 1):.1f}%")
    if args.svg:
        write_svg(args.svg, cpp_ms, python_ms, len(scans) * args.laps)
    return 0


if __name__ == "__main__":
    sys.exit(main())
