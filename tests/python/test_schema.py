"""`ballista schema`: a valid JSON Schema (draft 2020-12) that every shipped run deck and every
validation deck satisfies, and that catches what an editor should flag: a wrong type, a value out
of range, an unknown choice."""
import glob
import json
import os
import re

import jsonschema
import pytest
import yaml

from conftest import SOURCE, cli


class DeckLoader(yaml.SafeLoader):
    """YAML 1.2 as Ballista (yaml-cpp) and editors read it, not PyYAML's 1.1: 200e9 is a number,
    and only true/false are booleans (`adaptivity: on` is the word on)."""


DeckLoader.yaml_implicit_resolvers = {
    first: [(tag, regexp) for tag, regexp in resolvers if tag != "tag:yaml.org,2002:bool"]
    for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()}
DeckLoader.add_implicit_resolver("tag:yaml.org,2002:bool", re.compile(r"^(true|True|TRUE|false|False|FALSE)$"),
                                 list("tTfF"))
DeckLoader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^[-+]?\.(inf|Inf|INF)$|^\.(nan|NaN|NAN)$"),
    list("-+0123456789."))


def load(path):
    with open(path) as f:
        return yaml.load(f, Loader=DeckLoader)


@pytest.fixture(scope="module")
def schema(tmp_path_factory):
    out = tmp_path_factory.mktemp("schema") / "deck.schema.json"
    cli("schema", "-o", str(out))
    with open(out) as f:
        s = json.load(f)
    jsonschema.Draft202012Validator.check_schema(s)
    return s


def run_decks():
    decks = sorted(glob.glob(f"{SOURCE}/examples/*.yaml")) + sorted(glob.glob(f"{SOURCE}/validation/*.yaml"))
    return [d for d in decks if not os.path.basename(d).startswith("drive_")]


@pytest.mark.parametrize("deck", run_decks(), ids=os.path.basename)
def test_every_shipped_deck_satisfies_the_schema(schema, deck):
    jsonschema.Draft202012Validator(schema).validate(load(deck))


def test_the_registries_are_in_the_schema(schema):
    p = schema["properties"]
    models = p["materials"]["additionalProperties"]["properties"]["model"]["enum"]
    assert {"johnson_cook", "j2_plasticity", "neo_hookean"} <= set(models)
    assert {"mpm", "peridynamics", "otm"} <= set(p)  # the solvers' sections
    assert "max_radius" in p["probes"]["items"]["properties"]["type"]["enum"]
    assert "kg/m^3" in p["materials"]["additionalProperties"]["properties"]["density"]["description"]


@pytest.mark.parametrize("path, value", [
    (("grid", "cell_size"), "big"),              # a string for a number
    (("grid", "cell_size"), -1.0e-3),            # below its range (> 0)
    (("simulation", "solver"), "fem"),           # not a registered solver
    (("bodies", 0, "shape", "type"), "pyramid"),  # not a shape
    (("materials", "copper", "poisson_ratio"), 0.7),  # outside (-1, 0.5)
])
def test_the_schema_flags_what_an_editor_should(schema, path, value):
    deck = load(f"{SOURCE}/examples/taylor_bar_mpm.yaml")
    node = deck
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.Draft202012Validator(schema).validate(deck)


def test_the_schema_is_the_same_every_time(tmp_path):
    a = cli("schema").stdout
    b = cli("schema").stdout
    assert a == b and a.startswith("{")
