"""Ballista from Python: run decks, drive single material points, read results, evaluate the
analytic penetration models (docs/python.md).

    import ballista
    res = ballista.run("examples/taylor_bar_mpm.yaml", out_dir="out/taylor",
                       overrides={"grid.cell_size": 0.8e-3}, threads=2)
    print(res.status, res.summary["probes"], res.history["kinetic_energy"][-1])

    h = ballista.drive({"materials": {...}, "drive": {...}})      # one point, in memory
    print(h["sigma_11"][-1])

    ballista.models.evaluate("birkhoff", L=0.07354, rho_p=19235, rho_t=2300, V=3300)

Every number is in SI units, as in the decks (docs/deck.md).
"""
import os as _os
from pathlib import Path as _Path


def _installed_data_dir():
    """<prefix>/share/ballista when this package is installed as
    <prefix>/lib/python3.X/dist-packages/ballista (cmake --install, the Debian package)."""
    prefix = _Path(__file__).resolve().parents[4]
    share = prefix / "share" / "ballista"
    return str(share) if (share / "data" / "materials.yaml").is_file() else None


# The C++ core finds its presets and figure tools from the running executable, which here is the
# Python interpreter: point it at this installation's data unless the user chose a directory.
if not _os.environ.get("BALLISTA_DATA_DIR") and _installed_data_dir():
    _os.environ["BALLISTA_DATA_DIR"] = _installed_data_dir()
# OpenMP threads sleep while they wait, as the command line arranges (docs/performance.md); read
# by libgomp when the extension loads it, so set before the import below.
_os.environ.setdefault("OMP_WAIT_POLICY", "passive")

from . import _ballista  # noqa: E402
from ._ballista import DeckError, Error, PhysicsError  # noqa: E402
from . import models  # noqa: E402
from .drive import DriveHistory, drive  # noqa: E402
from .results import Results, Table  # noqa: E402
from .runs import run  # noqa: E402

__version__ = _ballista.version
#: `git describe` of the source tree the extension was built from ("-dirty": uncommitted changes).
commit = _ballista.commit

__all__ = ["run", "drive", "Results", "Table", "DriveHistory", "models", "Error", "DeckError",
           "PhysicsError", "commit", "__version__"]
