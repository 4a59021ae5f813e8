"""ballista.run: a deck run from Python is the command line's run, bit for bit; the progress
callback follows and stops it; a stopped run continues from its checkpoint; Results reads the
folder by body and material name."""
import json
import os
import signal

import h5py
import numpy as np
import pytest

from conftest import cli, example

TAYLOR = example("taylor_bar_mpm.yaml")
COARSE = {"grid.cell_size": 1.6e-3}  # 1.6 mm cells: ~800 steps, a second; the physics is not the point here


def same_particles(a, b):
    """Every dataset of the last particle file of two folders, exactly equal."""
    fa = sorted(f for f in os.listdir(a) if f.startswith("particles_") and f.endswith(".h5"))[-1]
    fb = sorted(f for f in os.listdir(b) if f.startswith("particles_") and f.endswith(".h5"))[-1]
    with h5py.File(os.path.join(a, fa)) as ha, h5py.File(os.path.join(b, fb)) as hb:
        assert sorted(ha.keys()) == sorted(hb.keys())
        for k in ha.keys():
            assert np.array_equal(ha[k][()], hb[k][()]), k


def read(path):
    with open(path) as f:
        return f.read()


@pytest.fixture(scope="module")
def cli_taylor(tmp_path_factory):
    out = tmp_path_factory.mktemp("cli") / "taylor"
    cli("run", TAYLOR, "-o", str(out), "--threads", "1", "-q", "--no-plots", "--set", "grid.cell_size=1.6e-3")
    return str(out)


def test_a_run_from_python_is_the_command_line_run(ballista, tmp_path, cli_taylor):
    res = ballista.run(TAYLOR, out_dir=tmp_path / "py", overrides=COARSE, threads=1, quiet=True)
    assert res.ok and res.status == "completed"
    assert read(os.path.join(res.dir, "history.csv")) == read(os.path.join(cli_taylor, "history.csv"))
    same_particles(res.dir, cli_taylor)
    with open(os.path.join(cli_taylor, "summary.json")) as f:
        assert res.summary["probes"] == json.load(f)["probes"]
    assert res.run_result["probes"] == res.summary["probes"]


def test_the_callback_stops_the_run_and_a_restart_ends_where_the_whole_run_ends(ballista, tmp_path, cli_taylor):
    reports = []

    def follow(report):
        reports.append(report)
        return report["fraction"] < 0.5

    out = tmp_path / "stopped"
    res = ballista.run(TAYLOR, out_dir=out, overrides=COARSE, threads=1, quiet=True, progress=follow,
                       progress_interval=0.0)
    assert res.status == "interrupted" and res.run_result["interrupted_by"] == "caller"
    assert res.run_result["checkpoint"] and os.path.isfile(res.run_result["checkpoint"])
    assert 0.5 <= reports[-1]["fraction"] < 0.6 and reports[-1]["phase"] == "main"
    steps = [r["step"] for r in reports]
    assert steps == sorted(steps) and all(r["end"] == pytest.approx(8e-5) for r in reports)
    done = ballista.run(restart=out, quiet=True)
    assert done.status == "completed"
    # Restarts are bitwise (docs/restart.md): the continued run ends in the uninterrupted state.
    same_particles(str(out), cli_taylor)


def test_an_exception_in_the_callback_stops_the_run_and_is_raised(ballista, tmp_path):
    calls = []

    def fail(report):
        calls.append(report)
        if len(calls) == 3:
            raise ValueError("enough")

    with pytest.raises(ValueError, match="enough"):
        ballista.run(TAYLOR, out_dir=tmp_path / "r", overrides=COARSE, threads=1, quiet=True, progress=fail,
                     progress_interval=0.0)
    assert len(calls) == 3
    assert ballista.Results(tmp_path / "r").status == "interrupted"


def test_ctrl_c_checkpoints_the_run_and_raises_keyboard_interrupt(ballista, tmp_path):
    def press_ctrl_c(report):
        if report["fraction"] > 0.2:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt, match="restart"):
        ballista.run(TAYLOR, out_dir=tmp_path / "c", overrides=COARSE, threads=1, quiet=True, progress=press_ctrl_c,
                     progress_interval=0.0)
    assert ballista.Results(tmp_path / "c").status == "interrupted"
    assert os.listdir(tmp_path / "c" / "checkpoints")


def disks_deck():
    """examples/elastic_disks.yaml written as a dict (Sulsky, Chen & Schreyer 1994, §5)."""
    disk = {"material": "soft", "particles_per_cell": 2}
    return {
        "simulation": {"solver": "mpm", "dimension": "plane_strain", "end_time": 3.0, "cfl": 0.1},
        "materials": {"soft": {"model": "neo_hookean", "density": 1000, "youngs_modulus": 1000, "poisson_ratio": 0.3}},
        "mpm": {"shape_function": "gimp", "update": "musl", "flip": 1.0},
        "grid": {"lower": [0.0, 0.0], "upper": [1.0, 1.0], "cell_size": 0.025},
        "bodies": [
            dict(disk, name="lower_left", velocity=[0.1, 0.1, 0],
                 shape={"type": "cylinder", "center": [0.25, 0.25, 0], "axis": "z", "radius": 0.2}),
            dict(disk, name="upper_right", velocity=[-0.1, -0.1, 0],
                 shape={"type": "cylinder", "center": [0.75, 0.75, 0], "axis": "z", "radius": 0.2}),
        ],
        "probes": [{"name": "kinetic_energy", "type": "energy", "field": "kinetic"},
                   {"name": "strain_energy", "type": "energy", "field": "internal"}],
        "output": {"interval": 0.5, "history_every": 5},
    }


def test_a_dict_deck_with_overrides_is_the_file_deck(ballista, tmp_path):
    probe = {"name": "vx_lower", "type": "mean_velocity", "body": "lower_left", "axis": "x"}
    res = ballista.run(disks_deck(), out_dir=tmp_path / "dict", threads=1, quiet=True,
                       overrides={"grid.cell_size": 0.05, "simulation.end_time": 1.0, "probes+": probe})
    cli("run", example("elastic_disks.yaml"), "-o", str(tmp_path / "file"), "--threads", "1", "-q", "--no-plots",
        "--set", "grid.cell_size=0.05", "--set", "simulation.end_time=1.0", "--set", "probes+=" + json.dumps(probe))
    assert read(tmp_path / "dict" / "history.csv") == read(tmp_path / "file" / "history.csv")
    h = res.history
    assert "vx_lower" in h.columns and len(h) > 10
    # Pure FLIP conserves the disks' energy (the deck's own check: drift below 1 %).
    total = h["kinetic_energy"] + h["strain_energy"]
    assert abs(total[-1] - total[0]) < 0.01 * total[0]
    # The disks approach each other: the lower one moves in +x until they touch (t ~ 0.5 s).
    assert h["vx_lower"][0] == pytest.approx(0.1, rel=1e-12)


def test_results_by_body_and_material_name(ballista, cli_taylor):
    res = ballista.Results(cli_taylor)
    assert res.body_names == ["bar"] and res.material_names == ["copper"]
    last = res.particles(fields=["x", "eqps", "body"])
    bar = res.particles(body="bar", material="copper", fields=["x"])
    assert bar["x"].shape == last["x"].shape and bar["time"] == pytest.approx(8e-5)
    assert [k for k, _, _ in res.outputs] == list(range(len(res.output_files())))
    with pytest.raises(KeyError, match="bar"):
        res.particles(body="rod")
    with pytest.raises(KeyError, match="eqps"):
        res.history["eqps"]
    with pytest.raises(FileNotFoundError, match="fragments.csv"):
        res.fragments
    # The axisymmetric bar's extensive fields are per radian of revolution, and their unit says so.
    with h5py.File(res.output_files()[-1]) as h:
        units = {k: h[k].attrs["unit"].decode() for k in ("mass", "volume", "internal_energy", "x", "stress")}
    assert units == {"mass": "kg/rad", "volume": "m^3/rad", "internal_energy": "J/rad", "x": "m", "stress": "Pa"}


def test_a_bad_deck_raises_naming_the_key(ballista, tmp_path):
    deck = disks_deck()
    deck["grid"]["cel_size"] = deck["grid"].pop("cell_size")
    with pytest.raises(ballista.DeckError) as e:
        ballista.run(deck, out_dir=tmp_path / "bad", quiet=True)
    assert e.value.key_path == "grid.cel_size" and "cell_size" in str(e.value)
    with pytest.raises(ValueError, match="out_dir"):
        ballista.run(disks_deck())


def test_fragments_come_back_as_a_table_that_adds_up_to_the_summary(ballista, tmp_path):
    # The expanding ring (peridynamics) at 1 mm: a fraction of a second, a few fragments.
    res = ballista.run(example("pd_expanding_ring.yaml"), out_dir=tmp_path / "ring", threads=1, quiet=True,
                       overrides={"grid.cell_size": 1e-3, "output.fields": []})  # every field
    assert res.ok
    s = res.summary["fragments"]
    f = res.fragments
    last = f["time"] == f["time"].max()
    assert f["time"].max() == pytest.approx(s["time"], rel=1e-12)
    assert last.sum() == s["count"] and s["count"] > 1
    # Mass is conserved into the fragments: their masses add up to the summary's total.
    assert f["mass"][last].sum() == pytest.approx(s["total_mass"], rel=1e-12)
    assert f["mass"][last].max() == pytest.approx(s["largest_mass"], rel=1e-12)
    assert any(line.startswith("fragments:") for line in res.headlines)
    # Plane stress: a point's mass is per metre of thickness, and its unit says so.
    with h5py.File(res.output_files()[-1]) as h:
        assert h["mass"].attrs["unit"].decode() == "kg/m" and h["x"].attrs["unit"].decode() == "m"


def test_a_second_run_from_another_thread_is_refused(ballista, tmp_path):
    import threading
    errors = []

    def second(report):
        if not errors:
            try:
                ballista.run(TAYLOR, out_dir=tmp_path / "second", overrides=COARSE, quiet=True)
                errors.append(None)
            except ballista.Error as e:
                errors.append(e)
        return False

    # The callback runs on the first run's thread; a thread started from it tries a second run.
    def from_thread(report):
        t = threading.Thread(target=second, args=(report,))
        t.start()
        t.join()
        return False

    res = ballista.run(TAYLOR, out_dir=tmp_path / "first", overrides=COARSE, threads=1, quiet=True,
                       progress=from_thread)
    assert res.status == "interrupted"
    assert isinstance(errors[0], ballista.Error) and "already going" in str(errors[0])


def test_a_run_that_fails_returns_its_results_and_says_why(ballista, tmp_path):
    # The energy guard set far below the run's residual: the run stops at a step with a physics
    # error, as `ballista run` does (exit 3), and leaves its folder with status "failed".
    res = ballista.run(TAYLOR, out_dir=tmp_path / "f", threads=1, quiet=True,
                       overrides=dict(COARSE, **{"simulation.energy_drift_limit": 1e-12}))
    assert res.status == "failed" and not res.ok
    assert "energy drift" in res.run_result["error"] and res.run_result["failed_step"] > 0
    assert res.summary["status"] == "failed" and "energy drift" in res.summary["error"]
