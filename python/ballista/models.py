"""The analytic penetration models of `ballista models` (docs/penetration_models.md): Birkhoff,
the particulated jet, Pack-Evans, Eichelberger, Alekseevskii-Tate, ... SI units throughout.

    from ballista import models
    models.names()                                   # ['birkhoff', 'particulated-jet', ...]
    models.describe("birkhoff")                      # equations, parameters with units
    r = models.evaluate("birkhoff", L=0.07354, rho_p=19235, rho_t=2300, V=3300)
    r["P"], r.units["P"]
    models.birkhoff(L=0.07354, rho_p=19235, rho_t=2300)   # the same, by attribute ('-' -> '_')

A parameter whose name is a Python keyword (`lambda`) is given as `lambda_` or in `params`.
"""
from . import _ballista


class ModelResult(dict):
    """A model's outputs {key: value} (a number, or a word for verdicts); `units[key]` its unit."""

    def __init__(self, name, outputs):
        super().__init__((o["key"], o["value"]) for o in outputs)
        self.name = name
        self.units = {o["key"]: o["unit"] for o in outputs}


def _catalog():
    return {m["name"]: m for m in _ballista.model_list()}


def names():
    """Every model's name, in the order of the thesis."""
    return [m["name"] for m in _ballista.model_list()]


def describe(name):
    """The model's entry: name, equations (their source), description, uses_series and params
    (key, unit, description, required, default)."""
    catalog = _catalog()
    if name not in catalog:
        raise KeyError(f"no model {name!r}; the models: {', '.join(catalog)}")
    return catalog[name]


def evaluate(name, params=None, *, velocities=None, rates=None, **kwargs):
    """Evaluates the model `name` with its parameters (SI units) from `params` and/or keywords;
    the fit models (`uses_series`) take the series `velocities` V and `rates` U (m/s). An unknown
    or missing parameter, or a result that is not a finite number, raises ballista.Error."""
    given = dict(params or {})
    for key, value in kwargs.items():
        key = key[:-1] if key.endswith("_") and key[:-1] == "lambda" else key
        if key in given:
            raise ValueError(f"parameter {key!r} given twice")
        given[key] = value
    outputs = _ballista.model_evaluate(name, {k: float(v) for k, v in given.items()},
                                       [float(v) for v in (velocities or [])], [float(u) for u in (rates or [])])
    return ModelResult(name, outputs)


def __getattr__(attr):
    """models.pack_evans(...) for the model 'pack-evans'."""
    catalog = _catalog()
    for name in catalog:
        if name.replace("-", "_") == attr:
            def model(params=None, **kwargs):
                return evaluate(name, params, **kwargs)
            model.__name__ = attr
            model.__doc__ = f"{name} ({catalog[name]['equations']}): {catalog[name]['description']}"
            return model
    raise AttributeError(f"module 'ballista.models' has no attribute {attr!r}")
