#!/usr/bin/python3
"""Writes a quarter of the Taylor bar (radius 3.2 mm, length 32.4 mm, axis y from y = 0; x >= 0,
z >= 0, cut by the symmetry planes x = 0 and z = 0) as an Exodus II mesh of tetrahedra in
millimetres, for OTM bodies seeded from their elements (examples/taylor_bar_otm_3d_mesh.yaml):

  /usr/bin/python3 examples/geometry/make_quarter_bar_tets.py examples/geometry/quarter_bar_tets.exo [--cell 0.8]

The quarter disk is the image of an n x n square grid (n = radius / cell, rounded) under the
concentric map of Shirley & Chiu (J. Graphics Tools 2 (1997) 45; its first octant: a square's
rings of nodes go to circles, so the quarter disk's edges on x = 0 and z = 0 are the square's and
its arc is the square's two far edges), extruded in layers of about `cell` along y. Each hexahedron
(planar faces: the bottom and top at constant y, the sides vertical) is cut into six tetrahedra
about one diagonal, the same in every hexahedron, so the tetrahedra tile it and meet their
neighbours face to face. The arc is 2n chords: the mesh holds sinc(pi / 4n) of the quarter
cylinder's volume (0.9936 at n = 4).
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exodus_writer import write_exodus  # noqa: E402

RADIUS, LENGTH = 3.2, 32.4  # mm
# The six tetrahedra of a hexahedron (corners numbered i + 2 j + 4 k over its three index
# directions) about its 0-7 diagonal: the paths 0 -> 7 through one corner at a time.
KUHN = ((0, 1, 3, 7), (0, 1, 5, 7), (0, 2, 3, 7), (0, 2, 6, 7), (0, 4, 5, 7), (0, 4, 6, 7))


def quarter_disk(n):
    """(n + 1)^2 points (x, z) of the mapped square grid, index i + (n + 1) j."""
    pts = []
    for j in range(n + 1):
        for i in range(n + 1):
            u, v = i / n, j / n
            if i == 0 and j == 0:
                x = z = 0.0
            elif u >= v:
                r, t = RADIUS * u, math.pi / 4 * v / u
                x, z = r * math.cos(t), r * math.sin(t)
            else:
                r, t = RADIUS * v, math.pi / 2 - math.pi / 4 * u / v
                x, z = r * math.cos(t), r * math.sin(t)
            if i == 0:
                x = 0.0  # on the symmetry plane exactly (cos(pi/2) is 6e-17)
            if j == 0:
                z = 0.0
            pts.append((x, z))
    return pts


def mesh(cell):
    n = max(1, round(RADIUS / cell))
    layers = max(1, round(LENGTH / cell))
    disk = quarter_disk(n)
    m = n + 1
    nodes = np.array([(x, LENGTH * k / layers, z) for k in range(layers + 1) for (x, z) in disk])

    def node(i, j, k):
        return i + m * j + m * m * k

    tets = []
    for k in range(layers):
        for j in range(n):
            for i in range(n):
                corner = [node(i + a, j + b, k + c) for c in (0, 1) for b in (0, 1) for a in (0, 1)]
                for t in KUHN:
                    tet = [corner[q] for q in t]
                    if volume(nodes, np.array([tet]))[0] < 0:
                        tet[1], tet[2] = tet[2], tet[1]
                    tets.append(tet)
    return nodes, np.array(tets, dtype=np.int32), n, layers


def volume(p, t):
    a, b, c, d = (p[t[:, i]] for i in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("path")
    ap.add_argument("--cell", type=float, default=0.8, help="element size, mm")
    a = ap.parse_args()
    p, tets, n, layers = mesh(a.cell)
    v = volume(p, tets)
    assert (v > 0).all(), "an inverted tetrahedron"
    write_exodus(a.path, f"Quarter Taylor bar, radius {RADIUS} mm, length {LENGTH} mm, {n} x {n} x {layers} "
                 "hexahedra in tetrahedra (Ballista examples/geometry)", p, [("bar", tets + 1, "TETRA")])
    exact = math.pi * RADIUS ** 2 * LENGTH / 4
    print(f"{a.path}: {len(p)} nodes, {len(tets)} tetrahedra, {v.sum():.4f} mm^3 "
          f"({v.sum() / exact:.4f} of the quarter cylinder)")


if __name__ == "__main__":
    main()
