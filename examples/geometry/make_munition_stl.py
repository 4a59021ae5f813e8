#!/usr/bin/python3
"""Writes the munition of examples/munition_case_pd.yaml as two binary STL surfaces in millimetres,
each a profile in the r-z plane revolved about the z axis with 128 facets around:

  munition_case.stl  the steel case: the exploding cylinder's tube (outer radius 16.13 mm, inner
                     12.7 mm, 98 mm long, open at z = 98 mm) closed at z = 0 by a 6 mm base whose
                     outer edge is chamfered at 45 degrees over 3 mm
  munition_fill.stl  the explosive filling the cavity (radius 12.7 mm, z = 0 to 98 mm)

  /usr/bin/python3 examples/geometry/make_munition_stl.py examples/geometry

A shape no primitive of the deck makes (a cup with a chamfer), as a CAD tool would export it.
"""
import math
import os
import sys

from make_cylinder_stl import write_stl  # the same folder: the binary STL writer

SIDES = 128
# Closed profiles (r, z) in mm, each traversed once; edges on the axis (r = 0) sweep nothing.
CASE = [(0.0, -6.0), (13.13, -6.0), (16.13, -3.0), (16.13, 98.0), (12.7, 98.0), (12.7, 0.0), (0.0, 0.0)]
FILL = [(0.0, 0.0), (12.7, 0.0), (12.7, 98.0), (0.0, 98.0)]


def revolve(profile):
    """Triangles of the surface swept by the closed profile's edges about z."""
    def point(r, z, k):
        a = 2 * math.pi * k / SIDES
        return (r * math.cos(a), r * math.sin(a), z)

    tris = []
    for (r0, z0), (r1, z1) in zip(profile, profile[1:] + profile[:1]):
        if r0 == 0.0 and r1 == 0.0:
            continue
        for k in range(SIDES):
            a0, a1 = point(r0, z0, k), point(r0, z0, k + 1)
            b0, b1 = point(r1, z1, k), point(r1, z1, k + 1)
            if r0 > 0.0:
                tris.append((a0, a1, b1))
            if r1 > 0.0:
                tris.append((a0, b1, b0))
    return tris


if __name__ == "__main__":
    folder = sys.argv[1] if len(sys.argv) > 1 else "."
    write_stl(os.path.join(folder, "munition_case.stl"), revolve(CASE), "Ballista munition case, mm")
    write_stl(os.path.join(folder, "munition_fill.stl"), revolve(FILL), "Ballista munition fill, mm")
