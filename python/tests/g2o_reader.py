"""A g2o text-format reader written from the format's published description (g2o's wiki "File Format"):
one element per line, `TAG id ... ` with VERTEX_SE3:QUAT id x y z qx qy qz qw, EDGE_SE3:QUAT id1 id2
x y z qx qy qz qw followed by the upper triangle of the 6x6 information matrix row by row, and the planar
VERTEX_SE2 id x y theta / EDGE_SE2 id1 id2 dx dy dtheta + the 3x3 upper triangle."""
import numpy as np


def quaternion_to_matrix(qx, qy, qz, qw):
    q = np.array([qw, qx, qy, qz], dtype=float)
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def se3(values):
    T = np.eye(4)
    T[:3, 3] = values[:3]
    T[:3, :3] = quaternion_to_matrix(*values[3:7])
    return T


def se2(x, y, theta):
    T = np.eye(4)
    c, s = np.cos(theta), np.sin(theta)
    T[:2, :2] = [[c, -s], [s, c]]
    T[:2, 3] = [x, y]
    return T


def upper_triangle(values, n):
    m = np.zeros((n, n))
    m[np.triu_indices(n)] = values
    return m + np.triu(m, 1).T


def read_g2o(path):
    """{'vertices': {id: 4x4}, 'edges': [(id1, id2, T 4x4, information n x n, tag)]}"""
    vertices, edges = {}, []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            fields = line.split()
            if not fields or fields[0].startswith("#"):
                continue
            tag, numbers = fields[0], fields[1:]
            if tag == "VERTEX_SE3:QUAT":
                assert len(numbers) == 8, f"line {number}: VERTEX_SE3:QUAT takes id + 7 numbers"
                vertices[int(numbers[0])] = se3([float(v) for v in numbers[1:]])
            elif tag == "VERTEX_SE2":
                assert len(numbers) == 4, f"line {number}: VERTEX_SE2 takes id + 3 numbers"
                vertices[int(numbers[0])] = se2(*[float(v) for v in numbers[1:]])
            elif tag == "EDGE_SE3:QUAT":
                assert len(numbers) == 2 + 7 + 21, f"line {number}: EDGE_SE3:QUAT takes 2 ids + 7 + 21 numbers"
                values = [float(v) for v in numbers[2:]]
                edges.append((int(numbers[0]), int(numbers[1]), se3(values[:7]), upper_triangle(values[7:], 6), tag))
            elif tag == "EDGE_SE2":
                assert len(numbers) == 2 + 3 + 6, f"line {number}: EDGE_SE2 takes 2 ids + 3 + 6 numbers"
                values = [float(v) for v in numbers[2:]]
                edges.append((int(numbers[0]), int(numbers[1]), se2(*values[:3]), upper_triangle(values[3:], 3), tag))
            else:
                raise ValueError(f"line {number}: unknown element {tag}")
    return {"vertices": vertices, "edges": edges}
