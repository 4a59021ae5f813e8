#!/usr/bin/python3
"""Writes the Taylor bar of examples/taylor_bar_mpm_3d.yaml (radius 3.2 mm, length 32.4 mm, axis y
from y = 0) as an Exodus II volume mesh in millimetres: block "core" (r < 1.6 mm) of tetrahedra,
three per sector prism, and block "skin" (1.6 mm < r < 3.2 mm) of hexahedra, 128 sectors around,
one element along the bar (the mesh only says where the copper is: the body is seeded with its
own lattice).

  /usr/bin/python3 examples/geometry/make_taylor_bar_exodus.py examples/geometry/taylor_bar.exo

The file is written by exodus_writer.py (scipy's netCDF writer). The 128-gon inscribed in the
circle has 0.9996 of its area, as the STL of taylor_bar_mpm_3d_surface.yaml.
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exodus_writer import write_exodus  # noqa: E402

RADIUS, LENGTH, SIDES = 3.2, 32.4, 128  # mm


def mesh():
    """Nodes (N, 3) and the two blocks' 1-based connectivities."""
    nodes = []
    index = {}

    def node(ring, k, layer):  # ring 0: the axis; 1: r = R/2; 2: r = R
        key = (ring, 0 if ring == 0 else k % SIDES, layer)
        if key not in index:
            r = RADIUS * ring / 2
            a = 2 * math.pi * key[1] / SIDES
            nodes.append((r * math.cos(a), LENGTH * layer, r * math.sin(a)))
            index[key] = len(nodes)
        return index[key]

    tets, hexes = [], []
    for k in range(SIDES):
        # The sector prism (axis, ring 1 at k, ring 1 at k+1) from y = 0 to y = L, in three
        # tetrahedra, each positive: the sector turns from +x towards +z, which with +y is
        # left-handed, so the bottom triangle is listed (axis, k+1, k).
        a0, b0, c0 = node(0, 0, 0), node(1, k + 1, 0), node(1, k, 0)
        a1, b1, c1 = node(0, 0, 1), node(1, k + 1, 1), node(1, k, 1)
        tets += [(a0, b0, c0, a1), (b0, c0, a1, b1), (c0, a1, b1, c1)]
        # The skin's hexahedron between the two rings, bottom face (y = 0) then top (y = L), in
        # the order that makes it positive.
        hexes.append((node(1, k, 0), node(1, k + 1, 0), node(2, k + 1, 0), node(2, k, 0),
                      node(1, k, 1), node(1, k + 1, 1), node(2, k + 1, 1), node(2, k, 1)))
    return np.array(nodes), np.array(tets, dtype=np.int32), np.array(hexes, dtype=np.int32)


def volume(p, t):
    a, b, c, d = (p[t[:, i] - 1] for i in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6


def write(path, node_map=True):
    """Writes the mesh to `path`; node_map=False leaves out the node number map (Ballista's
    reader then reads x by its workaround, exodus_writer.py: tests/python/test_mesh_bodies.py)."""
    p, tets, hexes = mesh()
    assert (volume(p, tets) > 0).all(), "a core tetrahedron is inverted"
    for split in ((0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)):
        assert (volume(p, hexes[:, split]) > 0).all(), "a skin hexahedron is inverted"
    write_exodus(path, "Taylor bar, radius 3.2 mm, length 32.4 mm (Ballista examples/geometry)", p,
                 [("core", tets, "TETRA"), ("skin", hexes, "HEX8")], node_map=node_map)
    print(f"{path}: {len(p)} nodes, {len(tets)} tetrahedra, {len(hexes)} hexahedra, "
          f"{volume(p, tets).sum() + sum(volume(p, hexes[:, s]).sum() for s in ((0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6))):.4f} mm^3")


if __name__ == "__main__":
    write(sys.argv[1] if len(sys.argv) > 1 else "taylor_bar.exo")
