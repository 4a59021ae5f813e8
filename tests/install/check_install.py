#!/usr/bin/env python3
"""An installed ballista works on its own: `cmake --install` (or the Debian package) into a
temporary root, then the installed binary run from there.

  tree     cmake --install BUILD --prefix OUT/prefix
  package  cpack -G DEB in BUILD, the package's control fields checked (its dependencies declared:
           the shared libraries by dpkg-shlibdeps, the Python packages of the figure tools), its
           files unpacked into OUT/root with dpkg-deb -x, and, where apt-get exists, a simulated
           `apt-get install ./ballista_*.deb` (does this Debian resolve every dependency?)

In both the installed binary must name its installed data directory (not the source tree it was
built from), read the material presets from there, and run an example deck, presets and figures
(the Python tools) included. The environment variables that redirect the lookup are removed, so
the test sees what a user sees.
"""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys

EXAMPLE = "rod_sandstone_mpm.yaml"  # a preset (sandstone), the penetration figures (tools/)
CI_SIZE = ["grid.cell_size=2.0e-3", "simulation.end_time=10.0e-6"]  # tests/examples' reduced size
FIGURES = ["penetration_depth.png", "channel_profile.png"]
WITH_PYTHON = True  # --no-python clears it


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def run(cmd, **kw):
    print("+", " ".join(cmd), flush=True)
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        fail(f"{' '.join(cmd)} exited {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r.stdout


def user_env():
    env = dict(os.environ)
    for key in ("BALLISTA_DATA_DIR", "BALLISTA_MATERIALS_FILE"):
        env.pop(key, None)
    return env


def check_installed(prefix, out):
    """The binary under PREFIX/bin finds PREFIX/share/ballista and runs an installed example."""
    exe = os.path.join(prefix, "bin", "ballista")
    share = os.path.join(prefix, "share", "ballista")
    for rel in ["data/materials.yaml", "tools/plot_penetration.py", "tools/read_output.py",
                "examples/" + EXAMPLE]:
        if not os.path.isfile(os.path.join(share, rel)):
            fail(f"{rel} not installed under {share}")
    env = user_env()
    version = run([exe, "--version"], env=env)
    if not version.startswith("ballista "):
        fail(f"--version printed {version!r}")
    # The deck schema is made by reading the installed examples (run/deck_schema.hpp).
    schema = json.loads(run([exe, "schema"], env=env))
    if "materials" not in schema.get("properties", {}):
        fail("`ballista schema` from the installed examples lists no materials section")
    info = run([exe, "info"], env=env)
    expected = f"Data directory (presets and tools; installed): {os.path.realpath(share)}"
    if expected not in info:
        fail(f"`ballista info` does not name the installed data directory; expected {expected!r} in:\n"
             + "\n".join(info.splitlines()[:3]))
    if os.path.realpath(os.path.join(share, "data", "materials.yaml")) not in info:
        fail("`ballista info` does not read the presets from the installed data directory")
    # The V&V report from the installed catalogue, tool and examples (one quick problem, 0.1 s).
    if WITH_PYTHON:
        vv = os.path.join(out, "validate")
        run([exe, "validate", "--only", "gurney_sandwich", "-o", vv, "--threads", "1"], env=env)
        if not os.path.isfile(os.path.join(vv, "report.html")):
            fail("`ballista validate` from the installed tree wrote no report.html")
    run_dir = os.path.join(out, "run")
    cmd = [exe, "run", os.path.join(share, "examples", EXAMPLE), "-o", run_dir, "--overwrite",
           "--threads", "1"]
    for s in CI_SIZE:
        cmd += ["--set", s]
    # Run from an empty directory: nothing may be found relative to the working directory.
    cwd = os.path.join(out, "cwd")
    os.makedirs(cwd, exist_ok=True)
    run(cmd, env=env, cwd=cwd)
    summary = json.load(open(os.path.join(run_dir, "summary.json")))
    if summary.get("status") != "completed":
        fail(f"the installed run ended with status {summary.get('status')!r}")
    for fig in FIGURES:
        if not os.path.isfile(os.path.join(run_dir, fig)):
            fail(f"the installed tools did not draw {fig}")
    if WITH_PYTHON:
        check_python_module(prefix, share, out, env, cwd)
    print(f"installed ballista under {prefix}: data directory found, {EXAMPLE} ran, figures drawn"
          + (", the Python module ran it too" if WITH_PYTHON else ""))


# Run by the installed module: it must be the installed one, point the core at the installed
# data (a preset), and run the example with its figures.
MODULE_CHECK = """
import os, sys
import ballista
prefix, share, example, out = sys.argv[1:5]
assert os.path.realpath(ballista.__file__).startswith(os.path.realpath(prefix)), ballista.__file__
assert os.path.realpath(os.environ["BALLISTA_DATA_DIR"]) == os.path.realpath(share), os.environ["BALLISTA_DATA_DIR"]
h = ballista.drive({"materials": {"cu": {"preset": "copper_ofhc_jc"}},
                    "drive": {"legs": [{"duration": 1e-4, "steps": 10, "strain": {"11": -0.01}}]}})
assert len(h) == 11
res = ballista.run(example, out_dir=out, overwrite=True, threads=1, quiet=True, plots=True,
                   overrides=[%s])
assert res.status == "completed", res.status
for fig in %r:
    assert os.path.isfile(os.path.join(out, fig)), fig
print("module", ballista.__version__, ballista.commit)
"""


def check_python_module(prefix, share, out, env, cwd):
    """The installed Python module (lib/python3.X/dist-packages/ballista) on its own."""
    found = glob.glob(os.path.join(prefix, "lib", "python3*", "dist-packages", "ballista", "__init__.py"))
    if len(found) != 1:
        fail(f"the Python module is not installed under {prefix}/lib/python3*/dist-packages: {found}")
    env = dict(env, PYTHONPATH=os.path.dirname(os.path.dirname(found[0])))
    script = MODULE_CHECK % (", ".join(repr(s) for s in CI_SIZE), FIGURES)
    run([sys.executable, "-c", script, prefix, share, os.path.join(share, "examples", EXAMPLE),
         os.path.join(out, "run_module")], env=env, cwd=cwd)


def tree(a):
    prefix = os.path.join(a.out, "prefix")
    shutil.rmtree(prefix, ignore_errors=True)
    run(["cmake", "--install", a.build, "--prefix", prefix])
    check_installed(prefix, a.out)


def package(a):
    pkg_dir = os.path.join(a.out, "package")
    shutil.rmtree(pkg_dir, ignore_errors=True)
    os.makedirs(pkg_dir)
    run(["cpack", "-G", "DEB", "-B", pkg_dir, "--config", os.path.join(a.build, "CPackConfig.cmake")])
    debs = glob.glob(os.path.join(pkg_dir, "ballista_*.deb"))
    if len(debs) != 1:
        fail(f"expected one ballista_*.deb in {pkg_dir}, found {debs}")
    deb = debs[0]
    depends = run(["dpkg-deb", "-f", deb, "Depends"])
    # dpkg-shlibdeps must have found the libraries the binary links, and the tools' Python
    # packages are declared by hand (cmake/install.cmake).
    for needed in ["libhdf5", "libyaml-cpp", "libgomp", "python3-matplotlib", "python3-h5py"]:
        if needed not in depends:
            fail(f"the package does not depend on {needed}: Depends: {depends}")
    root = os.path.join(a.out, "root")
    shutil.rmtree(root, ignore_errors=True)
    run(["dpkg-deb", "-x", deb, root])
    check_installed(os.path.join(root, "usr"), a.out)
    if shutil.which("apt-get"):
        sim = run(["apt-get", "install", "-s", "--no-install-recommends", os.path.abspath(deb)])
        if "Inst ballista" not in sim:
            fail("apt-get cannot resolve the package's dependencies:\n" + sim[-2000:])
        print("apt-get resolves every dependency of", os.path.basename(deb))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mode", choices=["tree", "package"])
    ap.add_argument("--build", required=True, help="the CMake build tree")
    ap.add_argument("--out", required=True)
    ap.add_argument("--no-python", action="store_true",
                    help="the tree has no Python module (a sanitized build: python/CMakeLists.txt)")
    a = ap.parse_args()
    global WITH_PYTHON
    WITH_PYTHON = not a.no_python
    a.out = os.path.abspath(a.out)
    os.makedirs(a.out, exist_ok=True)
    (tree if a.mode == "tree" else package)(a)
    print("PASS")


if __name__ == "__main__":
    main()
