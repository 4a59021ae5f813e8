#!/usr/bin/python3
"""Writes the Taylor bar of examples/taylor_bar_mpm_3d.yaml (radius 3.2 mm, length 32.4 mm, axis y
from y = 0) as an Exodus II volume mesh in millimetres: block "core" (r < 1.6 mm) of tetrahedra,
three per sector prism, and block "skin" (1.6 mm < r < 3.2 mm) of hexahedra, 128 sectors around,
one element along the bar (the mesh only says where the copper is: the body is seeded with its
own lattice).

  /usr/bin/python3 examples/geometry/make_taylor_bar_exodus.py examples/geometry/taylor_bar.exo

Exodus II is a netCDF file with named dimensions and variables (Schoof & Yarberry, "EXODUS II: A
Finite Element Data Model", SAND92-2137, 1994, ch. 3 and its netCDF mapping); scipy's netCDF
classic writer writes it, so no Exodus library is needed here. The 128-gon inscribed in the
circle has 0.9996 of its area, as the STL of taylor_bar_mpm_3d_surface.yaml.
"""
import math
import sys

import numpy as np
from scipy.io import netcdf_file

RADIUS, LENGTH, SIDES = 3.2, 32.4, 128  # mm
LEN_STRING, LEN_LINE = 33, 81           # Exodus II: MAX_STR_LENGTH + 1, MAX_LINE_LENGTH + 1


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


def chars(words, width):
    out = np.zeros((len(words), width), dtype="S1")
    for i, w in enumerate(words):
        for j, ch in enumerate(w.encode()):
            out[i, j] = bytes([ch])
    return out


def write(path, node_map=True):
    """Writes the mesh to `path`; node_map=False leaves out the node number map (the reader's
    workaround below is then what reads x: tests/python/test_mesh_bodies.py)."""
    p, tets, hexes = mesh()
    assert (volume(p, tets) > 0).all(), "a core tetrahedron is inverted"
    for split in ((0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)):
        assert (volume(p, hexes[:, split]) > 0).all(), "a skin hexahedron is inverted"
    f = netcdf_file(path, "w", version=2)
    f.api_version = np.float32(4.98)
    f.version = np.float32(4.98)
    f.floating_point_word_size = np.int32(8)
    f.file_size = np.int32(1)
    f.title = b"Taylor bar, radius 3.2 mm, length 32.4 mm (Ballista examples/geometry)"
    dims = {"len_string": LEN_STRING, "len_line": LEN_LINE, "four": 4, "num_dim": 3, "num_nodes": len(p),
            "num_elem": len(tets) + len(hexes), "num_el_blk": 2, "num_el_in_blk1": len(tets),
            "num_nod_per_el1": 4, "num_el_in_blk2": len(hexes), "num_nod_per_el2": 8}
    f.createDimension("time_step", None)  # scipy: the unlimited dimension first
    for name, size in dims.items():
        f.createDimension(name, size)
    f.createVariable("time_whole", "d", ("time_step",))
    status = f.createVariable("eb_status", "i", ("num_el_blk",))
    status[:] = [1, 1]
    ids = f.createVariable("eb_prop1", "i", ("num_el_blk",))
    ids[:] = [1, 2]
    ids.name = b"ID"
    f.createVariable("eb_names", "c", ("num_el_blk", "len_string"))[:] = chars(["core", "skin"], LEN_STRING)
    f.createVariable("coor_names", "c", ("num_dim", "len_string"))[:] = chars(["x", "y", "z"], LEN_STRING)
    # libexodusii 6.02 reads no x coordinates from a coordx that is the file's first variable
    # (netCDF id 0), and scipy writes the variables longest first, in creation order among equals:
    # the node number map (optional in Exodus II, the identity here) goes first.
    # (Ballista's reader works around it; other programs built on that library may not.)
    if node_map:
        f.createVariable("node_num_map", "i", ("num_nodes",))[:] = np.arange(1, len(p) + 1, dtype=np.int32)
    for k, axis in enumerate("xyz"):
        f.createVariable("coord" + axis, "d", ("num_nodes",))[:] = p[:, k]
    for blk, (conn, kind) in enumerate(((tets, b"TETRA"), (hexes, b"HEX8")), start=1):
        v = f.createVariable(f"connect{blk}", "i", (f"num_el_in_blk{blk}", f"num_nod_per_el{blk}"))
        v[:] = conn
        v.elem_type = kind
    f.close()
    print(f"{path}: {len(p)} nodes, {len(tets)} tetrahedra, {len(hexes)} hexahedra, "
          f"{volume(p, tets).sum() + sum(volume(p, hexes[:, s]).sum() for s in ((0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6))):.4f} mm^3")


if __name__ == "__main__":
    write(sys.argv[1] if len(sys.argv) > 1 else "taylor_bar.exo")
