#!/usr/bin/python3
"""Writes a closed cylinder as a binary STL: the Taylor bar of examples/taylor_bar_mpm_3d.yaml
(radius 3.2 mm, length 32.4 mm, axis y from y = 0), in millimetres, with 128 facets around.

  /usr/bin/python3 examples/geometry/make_cylinder_stl.py examples/geometry/taylor_bar.stl

The 128-gon inscribed in the circle has (128 / 2 pi) sin(2 pi / 128) = 0.9996 of its area.
"""
import math
import struct
import sys

RADIUS, LENGTH, SIDES = 3.2, 32.4, 128  # mm


def facets():
    ring = [(RADIUS * math.cos(2 * math.pi * k / SIDES), RADIUS * math.sin(2 * math.pi * k / SIDES))
            for k in range(SIDES)]
    for k in range(SIDES):
        (x0, z0), (x1, z1) = ring[k], ring[(k + 1) % SIDES]
        a0, a1, b0, b1 = (x0, 0.0, z0), (x1, 0.0, z1), (x0, LENGTH, z0), (x1, LENGTH, z1)
        yield (0.0, 0.0, 0.0), a1, a0           # bottom cap, wound outward (-y)
        yield (0.0, LENGTH, 0.0), b0, b1        # top cap (+y)
        yield a0, a1, b1                        # side
        yield a0, b1, b0


def write_stl(path, tris, title):
    """Binary STL: an 80-byte title, the count, and per triangle a zero normal, three corners."""
    with open(path, "wb") as f:
        f.write(title.encode().ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0.0, 0.0, 0.0))  # readers recompute normals from the winding
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(struct.pack("<H", 0))


def main(path):
    write_stl(path, list(facets()), "Ballista Taylor bar, mm")


if __name__ == "__main__":
    main(sys.argv[1])
