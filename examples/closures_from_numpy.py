#!/usr/bin/env python3
"""Streams a dataset through revisit's closure pipeline from numpy and prints the loop closures.

Usage: examples/closures_from_numpy.py DATASET   (e.g. sim:tiny, a KITTI folder, a rawlog)
With the dataset's reference poses when it has them, else revisit's own odometry."""
import sys

import numpy as np

import revisit

dataset = sys.argv[1] if len(sys.argv) > 1 else "sim:tiny"
config = revisit.load_config(dataset=dataset)  # the settings `revisit run` would derive from the data
pipeline = revisit.ClosurePipeline(config)

for scan in revisit.open_dataset(dataset, config):
    points = np.ascontiguousarray(scan.points, dtype=np.float32)  # (N, 3) in the sensor frame
    for closure in pipeline.add_scan(points, T_world_sensor=scan.T_world_sensor, stamp=scan.stamp):
        print(f"scan {scan.index}: map {closure.query_map} closes on map {closure.ref_map} "
              f"({closure.inliers} inliers, origins {np.linalg.norm(closure.T_query_ref[:3, 3]):.1f} m apart)")

closures = pipeline.finish()
corrected = pipeline.corrected_poses()  # (N, 4, 4) T_world_sensor after the pose graph
shift = np.linalg.norm(corrected[:, :3, 3] - pipeline.poses()[:, :3, 3], axis=1)
print(f"{len(closures)} closures over {pipeline.num_maps} maps; scans moved by up to {shift.max():.2f} m")
