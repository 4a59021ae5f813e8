"""Writes an Exodus II volume mesh (nodes and element blocks) for the mesh bodies of the examples.

Exodus II is a netCDF file with named dimensions and variables (Schoof & Yarberry, "EXODUS II: A
Finite Element Data Model", SAND92-2137, 1994, ch. 3 and its netCDF mapping); scipy's netCDF
classic writer writes it, so no Exodus library is needed here.
"""
import numpy as np
from scipy.io import netcdf_file

LEN_STRING, LEN_LINE = 33, 81  # Exodus II: MAX_STR_LENGTH + 1, MAX_LINE_LENGTH + 1


def chars(words, width):
    out = np.zeros((len(words), width), dtype="S1")
    for i, w in enumerate(words):
        for j, ch in enumerate(w.encode()):
            out[i, j] = bytes([ch])
    return out


def write_exodus(path, title, points, blocks, node_map=True):
    """points (N, 3); blocks: (name, 1-based connectivity (E, k), element type) per block.
    node_map=False leaves out the node number map (the reader's workaround below is then what
    reads x: tests/python/test_mesh_bodies.py)."""
    f = netcdf_file(path, "w", version=2)
    f.api_version = np.float32(4.98)
    f.version = np.float32(4.98)
    f.floating_point_word_size = np.int32(8)
    f.file_size = np.int32(1)
    f.title = title.encode()
    dims = {"len_string": LEN_STRING, "len_line": LEN_LINE, "four": 4, "num_dim": 3, "num_nodes": len(points),
            "num_elem": sum(len(conn) for _, conn, _ in blocks), "num_el_blk": len(blocks)}
    for b, (_, conn, _) in enumerate(blocks, start=1):
        dims[f"num_el_in_blk{b}"] = len(conn)
        dims[f"num_nod_per_el{b}"] = conn.shape[1]
    f.createDimension("time_step", None)  # scipy: the unlimited dimension first
    for name, size in dims.items():
        f.createDimension(name, size)
    f.createVariable("time_whole", "d", ("time_step",))
    status = f.createVariable("eb_status", "i", ("num_el_blk",))
    status[:] = [1] * len(blocks)
    ids = f.createVariable("eb_prop1", "i", ("num_el_blk",))
    ids[:] = list(range(1, len(blocks) + 1))
    ids.name = b"ID"
    f.createVariable("eb_names", "c", ("num_el_blk", "len_string"))[:] = chars([n for n, _, _ in blocks], LEN_STRING)
    f.createVariable("coor_names", "c", ("num_dim", "len_string"))[:] = chars(["x", "y", "z"], LEN_STRING)
    # libexodusii 6.02 reads no x coordinates from a coordx that is the file's first variable
    # (netCDF id 0), and scipy writes the variables longest first, in creation order among equals:
    # the node number map (optional in Exodus II, the identity here) goes first.
    # (Ballista's reader works around it; other programs built on that library may not.)
    if node_map:
        f.createVariable("node_num_map", "i", ("num_nodes",))[:] = np.arange(1, len(points) + 1, dtype=np.int32)
    for k, axis in enumerate("xyz"):
        f.createVariable("coord" + axis, "d", ("num_nodes",))[:] = points[:, k]
    for b, (_, conn, kind) in enumerate(blocks, start=1):
        v = f.createVariable(f"connect{b}", "i", (f"num_el_in_blk{b}", f"num_nod_per_el{b}"))
        v[:] = conn
        v.elem_type = kind.encode()
    f.close()
