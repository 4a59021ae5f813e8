"""A results folder read back: summary.json, the CSV tables and the particle files, with the
bodies and materials by name (docs/output.md describes every file, column and unit)."""
import csv
import glob
import json
import os

import numpy as np


class Table:
    """The columns of one CSV file as numpy arrays, under the file's own column names (probe
    names included as written). Numbers are float64 (`nan` where undefined); a column that is not
    numeric stays an array of str."""

    def __init__(self, path):
        self.path = os.fspath(path)
        with open(self.path, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
        if not rows:
            raise ValueError(f"{self.path}: empty file, no header")
        self.columns = rows[0]
        body = rows[1:]
        self._data = {}
        for j, name in enumerate(self.columns):
            cells = [r[j] if j < len(r) else "" for r in body]
            try:
                self._data[name] = np.array([float(c) for c in cells], dtype=float)
            except ValueError:
                self._data[name] = np.array(cells, dtype=str)

    def __getitem__(self, name):
        try:
            return self._data[name]
        except KeyError:
            raise KeyError(f"{self.path} has no column {name!r}; its columns: {', '.join(self.columns)}") from None

    def __contains__(self, name):
        return name in self._data

    def __iter__(self):
        return iter(self.columns)

    def __len__(self):
        """Rows."""
        return len(next(iter(self._data.values()))) if self._data else 0

    def keys(self):
        return list(self.columns)

    def items(self):
        return [(c, self._data[c]) for c in self.columns]

    def to_dict(self):
        return dict(self.items())

    def __repr__(self):
        return f"Table({self.path!r}: {len(self)} rows, {len(self.columns)} columns)"


class Results:
    """One results folder (`ballista run`, ballista.run). Opening it reads nothing; each
    attribute reads its file when asked. A file the run did not write raises FileNotFoundError
    naming it."""

    def __init__(self, out_dir, run_result=None):
        self.dir = os.fspath(out_dir)
        #: What ballista.run returned from the core (status, steps, probes, headlines, ...); None
        #: for a folder opened from disk.
        self.run_result = run_result
        self._summary = None

    def _path(self, name):
        path = os.path.join(self.dir, name)
        if not os.path.isfile(path):
            raise FileNotFoundError(f"{path}: this run did not write it (docs/output.md says which runs do)")
        return path

    @property
    def summary(self):
        """summary.json as a dict; its "units" entry names the SI unit of each number."""
        if self._summary is None:
            with open(self._path("summary.json"), encoding="utf-8") as f:
                self._summary = json.load(f)
        return self._summary

    @property
    def status(self):
        """"completed", "failed" or "interrupted"."""
        return self.summary.get("status")

    @property
    def ok(self):
        return self.status == "completed"

    @property
    def headlines(self):
        """The lines the run prints at its end (depth, holes, fragments, ...); [] when opened from disk."""
        return list(self.run_result["headlines"]) if self.run_result else []

    def table(self, name):
        """Any CSV file of the folder by its file name, e.g. "tracks/particle_7.csv"."""
        return Table(self._path(name))

    @property
    def history(self):
        return self.table("history.csv")

    @property
    def penetration(self):
        return self.table("penetration.csv")

    @property
    def channel(self):
        return self.table("channel.csv")

    @property
    def fragments(self):
        return self.table("fragments.csv")

    def output_files(self):
        """The particle files particles_NNNNNN.h5, in the order written."""
        return sorted(glob.glob(os.path.join(self.dir, "particles_[0-9]*.h5")))

    @property
    def outputs(self):
        """[(index, time in s, step)] of every particle output."""
        import h5py
        out = []
        for k, path in enumerate(self.output_files()):
            with h5py.File(path, "r") as h:
                out.append((k, float(h["time"][()]), int(h["step"][()])))
        return out

    def _names(self, attr):
        files = self.output_files()
        if not files:
            raise FileNotFoundError(f"{self.dir}: no particles_*.h5")
        import h5py
        with h5py.File(files[-1], "r") as h:
            return json.loads(h.attrs[attr])

    @property
    def body_names(self):
        """Body names in the order of `bodies:` (the `body` field's indices)."""
        return self._names("body_names")

    @property
    def material_names(self):
        """Material names in the order of `materials:` (the `material` field's indices)."""
        return self._names("material_names")

    def particles(self, index=-1, body=None, material=None, fields=None):
        """The points of one particle output as a dict of numpy arrays, one per field (x (N, 3),
        stress (N, 9) row-major, ...) plus "time" (s) and "step"; `index` counts outputs (negative
        from the end). `body` / `material`: only the points of that body or material, by name.
        `fields`: read only these (and the selection's own)."""
        import h5py
        files = self.output_files()
        if not files:
            raise FileNotFoundError(f"{self.dir}: no particles_*.h5")
        path = files[index]
        with h5py.File(path, "r") as h:
            names = [k for k in h.keys() if k not in ("time", "step", "vertex_cells")]
            if fields is not None:
                missing = [f for f in fields if f not in h]
                if missing:
                    raise KeyError(f"{path} has no field {', '.join(missing)}; it has: {', '.join(names)}")
                names = list(fields)
            rows = None
            for key, value, attr in (("body", body, "body_names"), ("material", material, "material_names")):
                if value is None:
                    continue
                known = json.loads(h.attrs[attr])
                if value not in known:
                    raise KeyError(f"{key} {value!r}: the run's {key} names are {', '.join(known)}")
                if key not in h:
                    raise KeyError(f"{path}: field {key!r} was not written (output.fields), so no selection by {key}")
                sel = h[key][()] == known.index(value)
                rows = sel if rows is None else rows & sel
            npoints = h["x"].shape[0]
            data = {}
            for name in names:
                ds = h[name]
                if ds.shape[:1] != (npoints,):
                    if rows is None:
                        data[name] = ds[()]  # OTM node datasets, domain cells: not per point
                    continue
                data[name] = ds[()] if rows is None else ds[()][rows]
            data["time"] = float(h["time"][()])
            data["step"] = int(h["step"][()])
        return data

    def __repr__(self):
        return f"Results({self.dir!r})"
