"""open_dataset: the CLI's readers, scans as numpy, checked against the files read directly with numpy."""
import numpy as np
import pytest

import revisit
from run_folder_files import read_kitti_poses


def test_scans_are_the_kitti_files(tiny):
    dataset = revisit.open_dataset(str(tiny))
    assert dataset.info["format"] == "kitti"
    bins = sorted((tiny / "velodyne").glob("*.bin"))
    assert len(dataset) == len(bins) == 1600
    reference = read_kitti_poses(tiny / "poses.txt")
    for scan in dataset:
        if scan.index == 3:
            break
    raw = np.fromfile(bins[3], dtype=np.float32).reshape(-1, 4)
    assert scan.points.dtype == np.float32 and scan.points.shape == (len(raw), 3)
    np.testing.assert_array_equal(scan.points, raw[:, :3])
    np.testing.assert_array_equal(scan.intensities, raw[:, 3])
    assert scan.T_world_sensor.shape == (4, 4)
    np.testing.assert_allclose(scan.T_world_sensor, reference[3], atol=1e-9)


def test_iterating_again_starts_over(tiny):
    dataset = revisit.open_dataset(str(tiny))
    first = next(iter(dataset))
    again = next(iter(dataset))
    assert first.index == again.index == 0
    np.testing.assert_array_equal(first.points, again.points)


def test_the_simulator_streams_as_a_dataset():
    scan = next(iter(revisit.open_dataset("sim:tiny")))
    assert scan.points.shape[1] == 3 and len(scan.points) > 1000


def test_a_missing_dataset_is_a_dataset_error_naming_it(tmp_path):
    with pytest.raises(revisit.DatasetError, match="no_such_folder"):
        revisit.open_dataset(str(tmp_path / "no_such_folder"))
