"""pose_graph.g2o and closures.json, read by readers written from the formats' descriptions; the g2o
graph re-optimized by revisit's own pose graph gives the run's corrected map poses."""
import json
import subprocess

import numpy as np
import pytest

import revisit
from g2o_reader import read_g2o
from run_folder_files import accepted_closures, pose, read_csv, read_kitti_poses

# g2o's SE(3) error takes the quaternion's vector part, revisit's graph twice it (pose_graph.hpp).
TO_REVISIT = np.diag([1.0, 1, 1, 0.5, 0.5, 0.5])


def assert_close(ours, theirs):
    if isinstance(ours, dict):
        assert ours.keys() == theirs.keys()
        for key in ours:
            assert_close(ours[key], theirs[key])
    elif isinstance(ours, (list, float)):
        np.testing.assert_allclose(np.array(ours), np.array(theirs), rtol=1e-6, atol=1e-7)
    else:
        assert ours == theirs


def test_g2o_holds_the_graph_of_the_run(cli_run):
    graph = read_g2o(cli_run / "pose_graph.g2o")
    maps = read_csv(cli_run / "local_maps.csv")
    closures = accepted_closures(cli_run)
    assert sorted(graph["vertices"]) == list(range(len(maps)))
    for row in maps:
        np.testing.assert_allclose(graph["vertices"][int(row["id"])], pose(row, "T_world_map"), atol=1e-6)
    odometry = [e for e in graph["edges"] if e[1] == e[0] + 1][: len(maps) - 1]
    loops = graph["edges"][len(maps) - 1:]
    assert [(a, b) for a, b, *_ in odometry] == [(i, i + 1) for i in range(len(maps) - 1)]
    assert [(a, b) for a, b, *_ in loops] == [(int(r["query"]), int(r["reference"])) for r in closures]
    for (_, _, T, information, tag), row in zip(loops, closures):
        assert tag == "EDGE_SE3:QUAT"
        np.testing.assert_allclose(T, pose(row, "T_query_ref_refined"), atol=1e-6)
        assert np.all(np.linalg.eigvalsh(information) > 0)


def test_g2o_round_trip_through_revisits_graph_gives_the_corrected_poses(cli_run):
    graph = read_g2o(cli_run / "pose_graph.g2o")
    nodes = np.stack([graph["vertices"][i] for i in sorted(graph["vertices"])])
    edges = [(a, b, T, TO_REVISIT @ information @ TO_REVISIT, k >= len(nodes) - 1)
             for k, (a, b, T, information, _) in enumerate(graph["edges"])]
    config = revisit.load_config(files=[str(cli_run / "config.yaml")])
    optimized = revisit.optimize_pose_graph(nodes, edges, config)
    corrected = np.stack([pose(row, "T_world_map_corrected") for row in read_csv(cli_run / "local_maps.csv")])
    moved = np.linalg.norm(corrected[:, :3, 3] - nodes[:, :3, 3], axis=1).max()
    assert moved > 0.0, "the closures moved the map origins"
    np.testing.assert_allclose(optimized[:, :3, 3], corrected[:, :3, 3], atol=1e-3)  # [m]
    np.testing.assert_allclose(optimized[:, :3, :3], corrected[:, :3, :3], atol=1e-5)


def test_per_scan_export_has_a_vertex_per_scan(cli, cli_run, tmp_path):
    out = tmp_path / "scans.g2o"
    subprocess.run([cli, "export", str(cli_run), "--format", "g2o", "--per-scan", "--out", str(out)], check=True,
                   stdout=subprocess.DEVNULL)
    graph = read_g2o(out)
    odometry = read_kitti_poses(cli_run / "poses_odometry_kitti.txt")
    assert len(graph["vertices"]) == len(odometry)
    np.testing.assert_allclose(graph["vertices"][1234], odometry[1234], atol=1e-6)
    maps = read_csv(cli_run / "local_maps.csv")
    first_scan = {int(m["id"]): int(m["first_scan"]) for m in maps}
    loops = graph["edges"][len(odometry) - 1:]
    assert [(a, b) for a, b, *_ in loops] == \
        [(first_scan[int(r["query"])], first_scan[int(r["reference"])]) for r in accepted_closures(cli_run)]


def test_export_of_the_finished_run_reproduces_the_runs_files(cli_run, tmp_path):
    g2o = revisit.export(str(cli_run), format="g2o", out=str(tmp_path / "graph.g2o"))
    again = read_g2o(g2o)
    original = read_g2o(cli_run / "pose_graph.g2o")
    assert len(again["edges"]) == len(original["edges"])
    for (a, b, T, info, _), (a0, b0, T0, info0, _) in zip(again["edges"], original["edges"]):
        assert (a, b) == (a0, b0)
        np.testing.assert_allclose(T, T0, atol=1e-6)
        np.testing.assert_allclose(info, info0, rtol=1e-6)
    exported = json.loads(open(revisit.export(str(cli_run), format="closures-json", out=str(tmp_path / "c.json"))).read())
    recorded = json.loads((cli_run / "closures.json").read_text())["closures"]
    assert len(exported["closures"]) == len(recorded)
    for ours, theirs in zip(exported["closures"], recorded):  # the run folder's text files keep 9 digits
        assert_close(ours, theirs)


def test_closures_json_lists_every_accepted_closure(cli_run):
    closures = json.loads((cli_run / "closures.json").read_text())["closures"]
    expected = accepted_closures(cli_run)
    assert len(closures) == len(expected) >= 1
    stamps = np.loadtxt(cli_run / "poses_odometry_tum.txt", ndmin=2)[:, 0]
    maps = {int(m["id"]): m for m in read_csv(cli_run / "local_maps.csv")}
    for c, row in zip(closures, expected):
        assert (c["query"]["map"], c["reference"]["map"]) == (int(row["query"]), int(row["reference"]))
        for end in (c["query"], c["reference"]):
            assert end["scan"] == int(maps[end["map"]]["first_scan"])
            assert abs(end["stamp"] - stamps[end["scan"]]) < 1e-6
        np.testing.assert_allclose(np.array(c["T_query_ref"]), pose(row, "T_query_ref_refined"), atol=1e-6)
        information, covariance = np.array(c["information"]), np.array(c["covariance"])
        np.testing.assert_allclose(covariance @ information, np.eye(6), atol=1e-6)


def test_occupancy_export_reads_back_as_map_server_reads_it(cli_run, tmp_path):
    """The run's grid redrawn at 1 m cells: the PGM's header and size agree with its YAML."""
    yaml_path = revisit.export(str(cli_run), format="occupancy", set={"occupancy.resolution": 1.0},
                               out=str(tmp_path / "grid.pgm"))
    fields = dict(line.split(": ", 1) for line in open(yaml_path).read().splitlines())
    assert fields["image"] == "grid.pgm" and fields["mode"] == "trinary" and float(fields["resolution"]) == 1.0
    magic, size, depth, pixels = (tmp_path / "grid.pgm").read_bytes().split(b"\n", 3)
    width, height = map(int, size.split())
    assert magic == b"P5" and depth == b"255" and len(pixels) == width * height
    pixels = np.frombuffer(pixels, dtype=np.uint8)
    assert set(np.unique(pixels)) <= {0, 205, 254} and (pixels == 0).any() and (pixels == 254).any()
    with pytest.raises(revisit.ConfigError, match="occupancy"):
        revisit.export(str(cli_run), format="occupancy", set={"graph.min_weight": 0.5}, out=str(tmp_path / "x.pgm"))
