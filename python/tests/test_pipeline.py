"""ClosurePipeline from numpy: the same closures and corrected poses as `revisit run` on the same data."""
import subprocess

import numpy as np
import pytest

import revisit
from run_folder_files import accepted_closures, pose, read_kitti_poses


def stream(dataset, config, to_points=lambda scan: scan.points, with_pose=True, last=None):
    pipeline = revisit.ClosurePipeline(config)
    online = []
    for scan in revisit.open_dataset(str(dataset), config):
        if last is not None and scan.index > last:
            break
        T = scan.T_world_sensor if with_pose else None
        online += pipeline.add_scan(to_points(scan), T_world_sensor=T, stamp=scan.stamp)
    return pipeline, online, pipeline.finish()


def with_intensity_float64(scan):
    return np.hstack([scan.points, scan.intensities[:, None]]).astype(np.float64)


@pytest.mark.parametrize("to_points", [lambda scan: scan.points, with_intensity_float64], ids=["float32 N x 3", "float64 N x 4"])
def test_streaming_numpy_gives_the_cli_closures_and_corrected_poses(tiny, cli_run, to_points):
    config = revisit.load_config(dataset=str(tiny))  # as `revisit run` resolves it
    pipeline, online, closures = stream(tiny, config, to_points=to_points)
    expected = accepted_closures(cli_run)
    assert expected, "the tiny drive's revisit closes a loop"
    assert online, "closures arrive while streaming, not only at finish()"
    assert [(c.query_map, c.ref_map, c.method) for c in closures] == \
        [(int(r["query"]), int(r["reference"]), r["method"]) for r in expected]
    for closure, row in zip(closures, expected):
        np.testing.assert_allclose(closure.T_query_ref, pose(row, "T_query_ref_refined"), atol=1e-6)
        assert closure.inliers == int(row["inliers"])
        assert closure.query_scans["first"] == int(row["query_first_scan"])
        assert closure.ref_scans["last"] == int(row["ref_last_scan"])
    corrected = pipeline.corrected_poses()
    cli_corrected = read_kitti_poses(cli_run / "poses_corrected_kitti.txt")
    assert corrected.shape == cli_corrected.shape == (1600, 4, 4)
    np.testing.assert_allclose(corrected, cli_corrected, atol=1e-6)
    assert pipeline.num_maps == len(open(cli_run / "local_maps.csv").readlines()) - 1


def test_without_poses_the_odometry_is_the_cli_odometry(cli, tiny, tmp_path):
    out = tmp_path / "odometry"
    subprocess.run([cli, "run", str(tiny), "--to", "299", "--out", str(out), "--quiet"], check=True, stdout=subprocess.DEVNULL)
    pipeline, _, _ = stream(tiny, revisit.load_config(dataset=str(tiny)), with_pose=False, last=299)
    np.testing.assert_allclose(pipeline.poses(), read_kitti_poses(out / "poses_odometry_kitti.txt"), atol=1e-6)
    np.testing.assert_allclose(pipeline.corrected_poses(), read_kitti_poses(out / "poses_corrected_kitti.txt"), atol=1e-6)


def test_bad_points_and_poses_are_python_errors():
    pipeline = revisit.ClosurePipeline(revisit.load_config())
    with pytest.raises(ValueError, match="N, 3"):
        pipeline.add_scan(np.zeros((10, 2), np.float32), np.eye(4))
    with pytest.raises(TypeError, match="float32 or float64"):
        pipeline.add_scan(np.zeros((10, 3), np.int32), np.eye(4))
    with pytest.raises(ValueError, match="4x4"):
        pipeline.add_scan(np.zeros((10, 3), np.float32), np.eye(3))
