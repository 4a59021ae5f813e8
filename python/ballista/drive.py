"""ballista.drive: one material point through an F-table or strain/stress legs (the deck of
`ballista drive`, docs/deck.md), in memory, fast enough to sit inside an optimiser's loop."""
import os

import numpy as np

from . import _ballista
from ._decks import deck_source, override_strings


class DriveHistory:
    """The driven point's history: one row per recorded step, the columns of `ballista drive`'s
    history.csv (step, t, F11..F33, sigma_11..sigma_12 (Pa), sigma_bar_*, I1, sqrt_J2, pressure,
    the model's state fields, plastic_work, plastic_work_total, internal_energy, iterations;
    docs/output.md). h["sigma_11"] is a numpy array; h.values the whole (rows, columns) array."""

    def __init__(self, raw):
        self.columns = list(raw["columns"])
        self.values = raw["values"]
        self.material = raw["material"]
        self.model = raw["model"]
        self.steps = raw["steps"]
        #: The deck with every default filled (what `ballista drive` writes as resolved.yaml).
        self.resolved_yaml = raw["resolved_yaml"]
        self._index = {c: j for j, c in enumerate(self.columns)}

    def __getitem__(self, name):
        try:
            return self.values[:, self._index[name]]
        except KeyError:
            raise KeyError(f"no column {name!r}; the columns: {', '.join(self.columns)}") from None

    def __contains__(self, name):
        return name in self._index

    def __len__(self):
        return self.values.shape[0]

    def keys(self):
        return list(self.columns)

    def stress(self):
        """The spatial Cauchy stress of every row as (rows, 3, 3), Pa."""
        s = np.empty((len(self), 3, 3))
        for (i, j), name in {(0, 0): "11", (1, 1): "22", (2, 2): "33", (1, 2): "23", (0, 2): "13",
                             (0, 1): "12"}.items():
            s[:, i, j] = s[:, j, i] = self[f"sigma_{name}"]
        return s

    def __repr__(self):
        return f"DriveHistory({self.material!r}, {self.model}: {len(self)} rows)"


def drive(deck, *, overrides=None, base_dir=None):
    """Drives one point of the deck's material (a drive deck's path, or a dict with `materials`
    (one) and `drive`) and returns its DriveHistory. `overrides` as for ballista.run, e.g.
    {"materials.cu.yield_stress": 9e7}. A bad deck raises DeckError; a point that cannot go on
    (non-finite stress, stress control not converging) raises PhysicsError whose `history`
    attribute holds the records up to the last good step."""
    text, file_name = deck_source(deck, base_dir)
    folder = os.path.dirname(os.path.abspath(file_name))
    raw = _ballista.drive_deck(text, file_name, override_strings(overrides), folder)
    history = DriveHistory(raw)
    if raw["error"]:
        err = _ballista.PhysicsError(raw["error"])
        err.history = history
        raise err
    return history
