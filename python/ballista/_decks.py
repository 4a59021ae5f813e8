"""A deck given as a file or as a dict, and overrides given as a dict or as --set strings,
turned into what the C++ core reads: YAML text, a file name for its messages, --set strings."""
import json
import os


def _plain(value):
    """numpy scalars and arrays as the Python numbers and lists JSON writes."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"a deck value of type {type(value).__name__} is not a number, string, list or dict")


def deck_source(deck, base_dir=None):
    """(text, file_name) of `deck`: a path (str or os.PathLike) to a YAML file, or a dict (written
    as JSON, which is YAML). A dict's relative paths (surface files, F-tables) are taken relative to
    `base_dir` (default: the working directory); its errors name it `<dict>` in that directory."""
    if isinstance(deck, dict):
        text = json.dumps(deck, indent=1, default=_plain)
        return text, os.path.join(os.path.abspath(base_dir or os.getcwd()), "<dict>")
    if isinstance(deck, (str, os.PathLike)):
        path = os.fspath(deck)
        if base_dir is not None:
            raise ValueError("base_dir is for a deck given as a dict; a file's paths are relative to its folder")
        with open(path, encoding="utf-8") as f:
            return f.read(), path
    raise TypeError(f"deck: a path to a YAML file or a dict, not {type(deck).__name__}")


def override_strings(overrides):
    """--set strings from a dict {key.path: value} ("key.path+" appends to a list) or an iterable
    of "key.path=value" strings; values are written as JSON (YAML flow style)."""
    if overrides is None:
        return []
    if isinstance(overrides, dict):
        out = []
        for key, value in overrides.items():
            if not isinstance(key, str) or not key:
                raise TypeError(f"override key {key!r}: a key path such as 'grid.cell_size'")
            if key.endswith("+"):
                out.append(f"{key[:-1]}+={json.dumps(value, default=_plain)}")
            else:
                out.append(f"{key}={json.dumps(value, default=_plain)}")
        return out
    if isinstance(overrides, str):
        return [overrides]
    return [str(s) for s in overrides]
