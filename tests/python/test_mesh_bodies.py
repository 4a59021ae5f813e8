"""A body from an Exodus II mesh written by another program than the Exodus library: the Taylor
bar's mesh of examples/geometry/make_taylor_bar_exodus.py, with and without the node number map
that puts `coordx` after the first netCDF variable, seeds the same points as the committed file
(libexodusii 6.02 reads zeros for a first-variable `coordx`; deck/mesh_reader.cpp reads it itself)."""
import importlib.util

import h5py
import numpy as np

from conftest import SOURCE, example


def generator():
    spec = importlib.util.spec_from_file_location("gen", f"{SOURCE}/examples/geometry/make_taylor_bar_exodus.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def seeded_points(ballista, mesh_file, out):
    res = ballista.run(example("taylor_bar_mpm_3d_mesh.yaml"), out_dir=out, threads=1, quiet=True,
                       overrides={"grid.cell_size": 1.0e-3, "simulation.end_time": 1e-9,
                                  "bodies.0.shape.file": str(mesh_file)})
    assert res.ok, res.run_result["error"]
    with h5py.File(res.output_files()[0]) as h:  # 3D: a point's mass is its own, in kg
        assert h["mass"].attrs["unit"].decode() == "kg"
    return res.particles(0, fields=["x"])["x"]


def test_a_mesh_whose_first_variable_is_coordx_seeds_the_same_points(ballista, tmp_path):
    gen = generator()
    gen.write(str(tmp_path / "plain.exo"), node_map=False)
    gen.write(str(tmp_path / "mapped.exo"), node_map=True)
    committed = seeded_points(ballista, f"{SOURCE}/examples/geometry/taylor_bar.exo", tmp_path / "c")
    plain = seeded_points(ballista, tmp_path / "plain.exo", tmp_path / "p")
    mapped = seeded_points(ballista, tmp_path / "mapped.exo", tmp_path / "m")
    assert len(committed) == 2015  # the analytic cylinder's count at 1 mm (taylor_bar_mpm_3d.yaml)
    assert np.array_equal(plain, committed) and np.array_equal(mapped, committed)
    # The bar fills r <= 3.2 mm (the quarter the symmetry planes keep), not a sliver at x = 0.
    r = np.hypot(plain[:, 0], plain[:, 2])
    assert r.max() <= 3.2e-3 and plain[:, 0].max() > 2.5e-3
