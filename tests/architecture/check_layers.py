#!/usr/bin/env python3
"""Checks every #include "<folder>/..." in src/ against the layer graph of cmake/layers.cmake.

All headers live under one include root (src/), so the compiler accepts an include of any layer;
this check is what makes an upward (or sideways) include fail. A file in src/<layer>/ may include
its own layer and every layer that <layer> reaches through DEPENDS in cmake/layers.cmake.

usage: check_layers.py SRC_DIR LAYER=DEP,DEP ...   (the graph as CMake passes it)
       check_layers.py --self-test                  (an upward include must be reported)
"""
import re
import sys
from pathlib import Path

INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def allowed_layers(graph):
    """Layer -> set of layers it may include (itself and everything below it)."""
    closure = {}

    def reach(layer):
        if layer not in closure:
            closure[layer] = {layer}
            for dep in graph[layer]:
                closure[layer] |= reach(dep)
        return closure[layer]

    for layer in graph:
        reach(layer)
    return closure


def main(argv):
    src = Path(argv[1])
    graph = {}
    for entry in argv[2:]:
        name, _, deps = entry.partition("=")
        graph[name] = [d for d in deps.split(",") if d]
    allowed = allowed_layers(graph)

    errors = []
    folders = sorted(p.name for p in src.iterdir() if p.is_dir())
    for folder in folders:
        if folder not in graph:
            errors.append(f"src/{folder}/: not a layer; declare it in cmake/layers.cmake")
    checked = 0
    for path in sorted(src.rglob("*")):
        if path.suffix not in (".hpp", ".cpp", ".h", ".inl") or not path.is_file():
            continue
        layer = path.relative_to(src).parts[0]
        if layer not in graph:
            continue
        for lineno, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            checked += 1
            target = m.group(1)
            top = target.split("/")[0] if "/" in target else None
            where = f"{path.relative_to(src.parent)}:{lineno}"
            if top is None:
                errors.append(f'{where}: #include "{target}": name the layer folder (e.g. "{layer}/{target}")')
            elif top not in graph:
                errors.append(f'{where}: #include "{target}": "{top}" is not a layer')
            elif top not in allowed[layer]:
                below = ", ".join(sorted(allowed[layer] - {layer})) or "nothing"
                errors.append(f'{where}: #include "{target}": layer {layer} may not use {top} '
                              f"(it may use: {below}; cmake/layers.cmake, docs/architecture.md)")
    for e in errors:
        print(e)
    print(f"check_layers: {checked} includes in {len(folders)} folders, {len(errors)} violation(s)")
    return 1 if errors else 0


def self_test():
    """A check that cannot fail is no check: plant an upward include and expect a violation."""
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "src"
        (src / "core").mkdir(parents=True)
        (src / "materials").mkdir()
        (src / "materials" / "m.hpp").write_text('#include "core/c.hpp"\n')
        (src / "core" / "c.hpp").write_text("#pragma once\n")
        graph = [str(src), "core=", "materials=core"]
        if main(["", *graph]) != 0:
            return 1
        (src / "core" / "c.hpp").write_text('#pragma once\n#include "materials/m.hpp"\n')
        if main(["", *graph]) == 0:
            print("self-test: the upward include core -> materials was not reported")
            return 1
    print("self-test: ok")
    return 0


if __name__ == "__main__":
    sys.exit(self_test() if sys.argv[1:] == ["--self-test"] else main(sys.argv))
