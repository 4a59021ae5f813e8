"""Deck builders of the fuzz harness (tools/fuzz_decks.py) for the newer solvers (issue 35):

  solver:<stem>   targeted mutations of the peridynamics, OTM and detonation decks: the solver's own
                  section keys (peridynamics.m, horizon, critical_stretch, fracture_energy, ...;
                  otm.gamma, support_tolerance, the adaptivity keys, ...), detonation.points
                  (inside, on, beside and far outside the charge, times up to 1e308, up to 1000
                  detonators), detonation.edge_radius and burn_cells, bodies[].point_spacing,
                  grid.boundary faces and an extra explosive material that no body uses;
  overlap:<stem>  two bodies that overlap by several lattice cells in every direction in which they
                  extend (a body shifted or grown into its neighbour, a fill radius grown into its
                  case, a shrunken copy of a body inside it), or that exactly touch (a shared face:
                  a body moved onto its neighbour's face, or one body split in two).

Each builder returns the deck as text with the reduced size written into it (no --set needed), the
mutation descriptions and, for overlap cases, the expectation: "overlap" with both body names, or
"touching". expectation_class() turns a run's outcome into the classes overlap_accepted (exit 0,
or a refusal that does not name both bodies, on a case built as a clear overlap) and
touching_refused (touching bodies refused with a message that contains "overlap").
"""
import math
import re

from fuzz_yaml import _copy, yaml_dump, yaml_load

MAX_STEPS = "30"

# Reduced sizes, written into the deck (dotted path -> value; list indices as numbers).
SOLVER_DECKS = {
    "pd_kalthoff_winkler": {"grid.cell_size": "2.0e-3", "simulation.end_time": "2.0e-6"},
    "pd_disk_indent": {"bodies.0.shape.radius": "0.0050001", "simulation.end_time": "1.0e-6"},
    "pd_expanding_ring": {"grid.cell_size": "1.0e-3", "simulation.end_time": "2.0e-6"},
    "exploding_cylinder_pd": {"grid.cell_size": "1.72e-3", "bodies.1.point_spacing": "3.44e-3",
                              "simulation.end_time": "1.0e-6"},
    "taylor_bar_otm": {"grid.cell_size": "0.8e-3", "simulation.end_time": "5.0e-6"},
    "taylor_bar_otm_750": {"grid.cell_size": "1.6e-3", "simulation.end_time": "5.0e-6"},
    "rod_plate_otm": {"grid.cell_size": "1.0e-3", "simulation.end_time": "3.0e-6"},
    "explosive_sandwich_mpm": {"grid.cell_size": "1.0e-3", "simulation.end_time": "3.0e-6"},
}
OVERLAP_DECKS = {
    "explosive_sandwich_mpm": {"grid.cell_size": "0.5e-3", "simulation.end_time": "2.0e-6"},
    "exploding_cylinder_pd": {"grid.cell_size": "1.72e-3", "bodies.1.point_spacing": "1.72e-3",
                              "simulation.end_time": "1.0e-6"},
    "pd_kalthoff_winkler": {"grid.cell_size": "2.0e-3", "simulation.end_time": "2.0e-6"},
    "jet_casing_sandstone_mpm": {"grid.cell_size": "2.0e-3", "grid.refine": "[]", "grid.patches": "[]",
                                 "mpm.multirate": "none", "simulation.end_time": "5.0e-6"},
    "rod_billet_4130_mpm": {"grid.cell_size": "1.0e-3", "simulation.end_time": "2.0e-6"},
    "elastic_disks": {"grid.cell_size": "0.05", "simulation.end_time": "0.05"},
    "taylor_bar_otm": {"grid.cell_size": "0.8e-3", "simulation.end_time": "2.0e-6"},
    "taylor_bar_mpm": {"grid.cell_size": "0.8e-3", "simulation.end_time": "2.0e-6"},
    "pd_expanding_ring": {"grid.cell_size": "1.0e-3", "simulation.end_time": "2.0e-6"},
    "pd_disk_indent": {"bodies.0.shape.radius": "0.0050001", "simulation.end_time": "1.0e-6"},
}

BAD = ["nan", "inf", "-inf", "abc", "[1]", "~", "\"\""]


def fl(x):
    return repr(float(x))


def set_dotted(tree, dotted, value):
    node = tree
    parts = dotted.split(".")
    for p in parts[:-1]:
        node = node[int(p)] if isinstance(node, list) else node.setdefault(p, {})
    last = parts[-1]
    if isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value


def _join_flow_lines(text):
    """Flow collections continued on the next lines joined into one line (the YAML subset reader
    takes a multi-line flow collection only as a map value)."""
    out, pending = [], None
    for line in text.splitlines():
        body = re.sub(r"\s#.*$", "", line)
        if pending is not None:
            pending += " " + body.strip()
        else:
            pending = body
        if pending.count("[") + pending.count("{") <= pending.count("]") + pending.count("}"):
            out.append(pending)
            pending = None
    if pending is not None:
        out.append(pending)
    return "\n".join(out) + "\n"


def reduced_tree(text, reductions):
    tree = yaml_load(_join_flow_lines(text))
    for k, v in reductions.items():
        set_dotted(tree, k, v)
    tree.setdefault("simulation", {})["max_steps"] = MAX_STEPS
    return tree


def dump(tree):
    return (yaml_dump(tree) + "\n").encode()


def _dim3(tree):
    return str(tree.get("simulation", {}).get("dimension", "3d")) == "3d"


def _body(tree, name):
    return next(b for b in tree["bodies"] if isinstance(b, dict) and b.get("name") == name)


# ---------------------------------------------------------------------------------------------
# solver: targeted mutations
# ---------------------------------------------------------------------------------------------
def pd_values(key, dx, dim3):
    """Values for a peridynamics key. Horizons comparable to the body only in 2D: in 3D they build
    every pair of points (8-12 s at the reduced sizes: a hang or not by the machine's load)."""
    if key == "m":
        return ["1", "1.5", "2", "2.5", "3", "3.0001", "4", "5", "6", "20", "0", "0.99", "-3", "20.5", "21",
                "1e308"] + BAD
    if key == "horizon":
        v = [fl(k * dx) for k in (0.5, 0.99, 1, 1.01, 1.5, 2, 3.0001, 4, 6)] + ["0", "-1e-3", "1e-300"] + BAD
        return v + ([fl(25 * dx), "0.05", "1", "1e30", "1e308"] if not dim3 else [])
    return {
        "thickness": ["1e-9", "1e-3", "0.009", "1", "1e308", "0", "-0.009"] + BAD,
        "critical_stretch": ["1e-12", "1e-6", "5e-4", "0.01", "0.15", "1", "10", "1e308", "0", "-0.1"] + BAD,
        "fracture_energy": ["1e-30", "1", "2.2e4", "1e6", "1e30", "1e308", "0", "-1"] + BAD,
        "yield_stress": ["1", "1e6", "750e6", "1e9", "1e12", "1e308", "0", "-7.5e8"] + BAD,
        "stretch_scatter": ["0", "1e-9", "0.1", "0.3", "0.3000001", "0.31", "1", "-0.1"] + BAD,
        "stretch_alpha": ["0", "0.25", "1", "100", "1e308", "-0.25"] + BAD,
        "gas_refamily_steps": ["0", "1", "2", "5", "1000", "1000000", "1000001", "-1", "2.5", "1e308"] + BAD,
        "dt_safety": ["1e-9", "0.1", "0.8", "1", "1.0000001", "0", "-0.8"] + BAD,
        "fragment_interval": ["0", "1e-12", "1e-9", "1e-7", "1", "1e308", "-1"] + BAD,
        "fragment_damage_threshold": ["0", "0.5", "0.95", "1", "1.01", "-0.1"] + BAD,
        "contact": ["on", "off", "yes", "1"],
        "contact_pairs": ["unbonded", "all", "none"],
        "break_rule": ["work", "lammps", "x"],
        "contact_skin": ["1e-9", "0.01", "0.5", "10", "10.01", "0"] + BAD,
        "volume_correction": ["partial", "none", "full"],
        "calibration": ["lattice", "continuum", "x"],
        "surface_correction": ["none", "energy", "x"],
    }[key]


PD_KEYS = ["m", "m", "horizon", "horizon", "horizon", "critical_stretch", "fracture_energy", "yield_stress",
           "stretch_scatter", "stretch_alpha", "thickness", "thickness", "gas_refamily_steps", "gas_refamily_steps",
           "dt_safety", "fragment_interval", "fragment_damage_threshold", "contact", "contact_pairs", "break_rule",
           "contact_skin", "volume_correction", "calibration", "surface_correction"]
OTM_VALUES = {
    "gamma": ["1e-300", "0.01", "0.1", "0.8", "1.8", "4", "10", "49.99", "50", "50.0001", "0", "-1.8"] + BAD,
    "support_tolerance": ["1e-300", "1e-12", "1e-6", "1e-4", "0.01", "0.1", "0.1000001", "0", "-1e-4"] + BAD,
    "min_support": ["0", "1", "2", "3", "4", "8", "30", "1000", "1001", "-1", "2.5"] + BAD,
    "wall_model": ["constraint", "penalty", "bogus"],
    "penalty": ["1e-300", "1e-6", "1", "100", "100.0001", "0", "-1"] + BAD,
    "line_search": ["on", "off", "true"],
    "adaptivity": ["on", "on", "off", "auto"],
    "split_stretch": ["1", "1.0000001", "1.01", "2", "100", "100.1"] + BAD,
    "node_gap": ["1e-300", "1e-3", "0.5", "1", "100", "101", "0"] + BAD,
    "node_crowding": ["0", "0.25", "0.99", "1", "1.0001", "-0.1"] + BAD,
    "max_condition": ["1", "1.0001", "10", "1e6", "1e300", "1e301", "1e308", "0"] + BAD,
    "nodes": ["per_body", "shared", "both"],
}
MPM_VALUES = {
    "flip": ["0", "0.5", "0.99", "1", "1.01"] + BAD,
    "update": ["usl", "musl", "usavg", "x"],
    "shape_function": ["linear", "gimp", "cpdi", "bspline3", "x"],
    "bulk_viscosity_linear": ["0", "0.06", "0.2", "10", "10.1"] + BAD,
    "bulk_viscosity_quadratic": ["0", "1.5", "2", "100", "101"] + BAD,
    "bulk_viscosity_sound_speed": ["current", "reference", "x"],
    "xpic_order": ["1", "2", "8", "9", "0"] + BAD,
    "distortion_limit": ["0", "0.5", "1", "1000", "1e12", "1.1e12", "-1"] + BAD,
}


def _pick(rng, values):
    """A value of the list; the malformed ones (BAD) only one time in five, so that most cases
    pass the deck checks and reach the solver."""
    good = [v for v in values if v not in BAD]
    bad = [v for v in values if v in BAD]
    return rng.choice(bad if bad and (not good or rng.random() < 0.2) else good)


def _error_line(text):
    lines = [l.strip() for l in text.splitlines() if l.strip()]
    for l in lines:
        if re.search(r"error|FAILED|refus", l, re.IGNORECASE):
            return l
    return lines[-1] if lines else ""


def mutate_solver_key(rng, tree, ctx):
    solver = tree["simulation"]["solver"]
    sec = tree.setdefault(solver, {})
    if not isinstance(sec, dict):
        sec = tree[solver] = {}
    if solver == "peridynamics":
        key = rng.choice(PD_KEYS)
        values = pd_values(key, ctx["dx"], ctx["dim3"])
    elif solver == "otm":
        key = rng.choice(list(OTM_VALUES) + ["gamma", "support_tolerance", "adaptivity", "node_gap",
                                             "split_stretch", "max_condition"])
        values = OTM_VALUES[key]
    else:
        key = rng.choice(list(MPM_VALUES))
        values = MPM_VALUES[key]
    op = rng.random()
    if op < 0.08 and key in sec:
        del sec[key]
        return f"delete {solver}.{key}"
    if op < 0.13:
        typo = key[:-1] if len(key) > 2 else key + "x"
        sec[typo] = _pick(rng, values)
        return f"unknown key {solver}.{typo} (must be rejected)"
    v = _pick(rng, values)
    sec[key] = v
    desc = f"{solver}.{key} = {v}"
    if solver == "peridynamics" and key == "horizon" and "m" in sec and rng.random() < 0.75:
        del sec["m"]  # give the horizon instead of m (both: a deck error)
        desc += " (m deleted)"
    if solver == "peridynamics" and key == "m" and "horizon" in sec and rng.random() < 0.75:
        del sec["horizon"]
        desc += " (horizon deleted)"
    if solver == "otm" and key in ("split_stretch", "node_gap", "node_crowding", "max_condition") \
            and rng.random() < 0.7:
        sec["adaptivity"] = "on"
        desc += " (adaptivity on)"
    return desc


def _charge(tree):
    mats = tree.get("materials", {})
    explosive = {n for n, m in mats.items() if isinstance(m, dict) and (
        m.get("model") == "explosive" or m.get("preset") in ("tnt", "comp_b", "lx14_pbxn9_standin"))}
    for b in tree.get("bodies", []):
        if isinstance(b, dict) and b.get("material") in explosive and isinstance(b.get("shape"), dict):
            return b
    return None


def point_in_shape(rng, shape, dim3, where="inside"):
    """A point inside a box or a cylinder (base centre, axis), or just outside it (where="outside":
    1.5 - 3 cells beyond the surface is the caller's business: here 10 % beyond its size)."""
    t = shape.get("type")
    nd = 3 if dim3 else 2
    if t == "box":
        lo, up = [float(x) for x in shape["lower"]], [float(x) for x in shape["upper"]]
        p = [rng.uniform(lo[i], up[i]) for i in range(nd)]
        if where == "outside":
            i = rng.randrange(nd)
            p[i] = up[i] + 0.1 * (up[i] - lo[i]) + 1e-4 if rng.random() < 0.5 else lo[i] - 0.1 * (up[i] - lo[i]) - 1e-4
        return p
    c = [float(x) for x in shape["center"]] + [0.0] * 3
    ax = "xyz".index(shape.get("axis", "z"))
    r = float(shape["radius"])
    length = float(shape.get("length", 0) or 0)
    rad = r * math.sqrt(rng.random()) if where == "inside" else r * 1.1 + 1e-4
    phi = rng.uniform(0, 2 * math.pi)
    others = [i for i in range(3) if i != ax]
    p = list(c[:3])
    p[others[0]] += rad * math.cos(phi)
    p[others[1]] += rad * math.sin(phi)
    p[ax] += rng.uniform(0, length)
    return p[:nd]


def mutate_detonation(rng, tree, ctx):
    det = tree.setdefault("detonation", {})
    charge = _charge(tree)
    dim3 = ctx["dim3"]
    end = float(tree["simulation"]["end_time"])
    op = rng.choice(["position", "position", "time", "time", "many", "many", "empty", "edge_radius",
                     "burn_cells"])
    pts = det.get("points")
    if not isinstance(pts, list) or not pts or not isinstance(pts[0], dict):
        pts = det["points"] = [{"position": [fl(0)] * (3 if dim3 else 2), "time": "0"}]
    if op == "position":
        where = rng.choice(["inside", "inside", "outside", "other_body", "far", "extreme", "dimension"])
        if where in ("inside", "outside") and charge:
            p = [fl(x) for x in point_in_shape(rng, charge["shape"], dim3, where)]
        elif where == "other_body":
            others = [b for b in tree["bodies"] if isinstance(b, dict) and b is not charge
                      and isinstance(b.get("shape"), dict)]
            p = [fl(x) for x in point_in_shape(rng, others[0]["shape"], dim3)] if others else ["0"] * 3
        elif where == "far":
            up = [float(x) for x in tree["grid"]["upper"]]
            p = [fl(2 * abs(x) + 1) for x in up]
        elif where == "extreme":
            p = [rng.choice(["1e308", "-1e308", "nan", "inf", "0"]) for _ in range(3 if dim3 else 2)]
        else:
            p = [fl(0)] * (2 if dim3 else 3)
        pts[0]["position"] = p
        return f"detonation.points.0.position = [{', '.join(p)}] ({where})"
    if op == "time":
        v = _pick(rng, ["0", "1e-9", "-1e-6", "1e308", "-1e308", "1e-300", fl(end * 0.5), fl(end * 2), "nan",
                        "inf", "abc"])
        pts[0]["time"] = v
        return f"detonation.points.0.time = {v}"
    if op == "many":
        n = rng.choice([2, 10, 100, 1000])
        same = rng.random() < 0.2
        first = point_in_shape(rng, charge["shape"], dim3) if charge else [0.0] * (3 if dim3 else 2)
        new = []
        for i in range(n):
            p = first if same or not charge else point_in_shape(rng, charge["shape"], dim3)
            new.append({"position": [fl(x) for x in p], "time": fl(rng.uniform(0, end)) if i and rng.random() < 0.5
                        else "0"})
        det["points"] = new
        return f"detonation.points: {n} detonators in the charge" + (" (all at one point)" if same else "")
    if op == "empty":
        form = rng.randrange(3)
        if form == 0:
            det["points"] = []
            return "detonation.points = []"
        if form == 1:
            del det["points"]
            return "delete detonation.points"
        del tree["detonation"]
        return "delete detonation"
    if op == "edge_radius":
        v = _pick(rng, ["1.5", "1.49", "2", "3.2", "10", "10.01", "0", "-3.2", "1e308"] + BAD)
        det["edge_radius"] = v
        return f"detonation.edge_radius = {v}"
    v = _pick(rng, ["0", "0.5", "2", "100", "1e6", "1e308", "-1"] + BAD)
    det["burn_cells"] = v
    return f"detonation.burn_cells = {v}"


def mutate_point_spacing(rng, tree, ctx):
    bodies = [i for i, b in enumerate(tree["bodies"]) if isinstance(b, dict)]
    charge = _charge(tree)
    i = tree["bodies"].index(charge) if charge and rng.random() < 0.6 else rng.choice(bodies)
    dx = ctx["dx"]
    v = _pick(rng, [fl(k * dx) for k in (0.5, 0.99, 1, 1.5, 2, 3, 4.3)] + ["0", "-1e-3", "1e308", "1e-9"] + BAD)
    tree["bodies"][i]["point_spacing"] = v
    return f"bodies.{i}.point_spacing = {v} ({tree['bodies'][i].get('name')})"


def mutate_boundary(rng, tree, ctx):
    faces = ["x_min", "x_max", "y_min", "y_max"] + (["z_min", "z_max"] if ctx["dim3"] else [])
    b = tree["grid"].get("boundary")
    if not isinstance(b, dict) or rng.random() < 0.3:
        b = tree["grid"]["boundary"] = {}
    chosen = rng.sample(faces, rng.choice([1, 1, 2, len(faces)]))
    for f in chosen:
        b[f] = rng.choice(["symmetry", "symmetry", "fixed", "fixed", "wall", "wall", "free", "slip"])
    if rng.random() < 0.05:
        b["w_min"] = "wall"
        return f"grid.boundary = {{{', '.join(f'{k}: {v}' for k, v in b.items())}}} (unknown face: must be rejected)"
    return f"grid.boundary = {{{', '.join(f'{k}: {v}' for k, v in b.items())}}}"


EXTRA_EXPLOSIVES = [
    {"preset": "comp_b"}, {"preset": "tnt"}, {"preset": "lx14_pbxn9_standin"},
    {"model": "explosive", "density": "1630", "detonation_speed": "6930", "products": "ideal_gas"},
    {"model": "explosive", "density": "1630", "detonation_speed": "6930", "cj_pressure": "21e9"},
    {"model": "explosive", "density": "0", "detonation_speed": "6930"},
    {"model": "explosive", "density": "1630", "detonation_speed": "1e308", "products": "ideal_gas"},
]


def mutate_extra_explosive(rng, tree, ctx):
    m = _copy(rng.choice(EXTRA_EXPLOSIVES))
    tree["materials"]["fuzz_unused_explosive"] = m
    desc = "materials.fuzz_unused_explosive = {" + ", ".join(f"{k}: {v}" for k, v in m.items()) + "} (no body uses it)"
    if "detonation" not in tree and rng.random() < 0.8:  # past the check that an explosive needs a detonator
        tree["detonation"] = {"points": [{"position": ["0.0"] * (3 if ctx["dim3"] else 2), "time": "0"}]}
        desc += " with a detonator at the origin"
    return desc


def solver_deck(rng, text, stem, mut):
    """(deck bytes, descriptions) for solver:<stem>."""
    tree = reduced_tree(text, SOLVER_DECKS[stem])
    if not mut:
        return dump(tree), []
    ctx = {"dx": float(tree["grid"]["cell_size"]), "dim3": _dim3(tree)}
    has_det = "detonation" in tree
    ops = [(mutate_solver_key, 0.1 if tree["simulation"]["solver"] == "mpm" else 0.55),
           (mutate_detonation, 0.5 if has_det else 0.0), (mutate_point_spacing, 0.1), (mutate_boundary, 0.15),
           (mutate_extra_explosive, 0.07)]
    descs = []
    for _ in range(rng.choice([1, 1, 1, 2, 2, 3])):
        f = rng.choices([o[0] for o in ops], weights=[o[1] for o in ops])[0]
        descs.append(f(rng, tree, ctx))
    return dump(tree), descs


# ---------------------------------------------------------------------------------------------
# overlap: overlapping and touching bodies
# ---------------------------------------------------------------------------------------------
def _ov_sandwich(rng, t, dx, touching):
    ch, pl = _body(t, "charge")["shape"], _body(t, "plate")["shape"]
    if touching:
        a = rng.uniform(6e-3, 14e-3)
        if rng.random() < 0.5:
            a = round(a / dx) * dx  # on a cell face
        ch["upper"][0] = fl(a)
        pl["lower"][0], pl["upper"][0] = fl(a), fl(a + 2.076e-3)
        return f"charge and plate touch at x = {a:.6g} m", ("charge", "plate")
    k = rng.choice([3, 4, 6, 10])
    d = k * dx
    op = rng.randrange(3)
    if op == 0:
        pl["lower"][0] = fl(10e-3 - d)
        return f"plate grown {k} cells into the charge (lower x = {10e-3 - d:.6g})", ("charge", "plate")
    if op == 1:
        ch["upper"][0] = fl(10e-3 + d)
        return f"charge grown {k} cells into the plate (upper x = {10e-3 + d:.6g})", ("charge", "plate")
    pl["lower"][0], pl["upper"][0] = fl(10e-3 - d), fl(12.076e-3 - d)
    return f"plate shifted {k} cells into the charge", ("charge", "plate")


def _ov_cylinder(rng, t, dx, touching):
    case, ch = _body(t, "case")["shape"], _body(t, "charge")["shape"]
    if touching:
        r = rng.uniform(9e-3, 14e-3)
        ch["radius"], case["inner_radius"], case["radius"] = fl(r), fl(r), fl(r + 3.43e-3)
        return f"charge radius = case inner radius = {r:.6g} m (outer {r + 3.43e-3:.6g})", ("case", "charge")
    op = rng.randrange(3)
    if op == 0:
        k = rng.choice([3, 4, 5])
        case["inner_radius"] = fl(12.7e-3 - k * dx)
        return f"case inner radius {k} cells into the charge ({12.7e-3 - k * dx:.6g} m)", ("case", "charge")
    if op == 1:
        j = rng.choice([0, 1, 2, 4])
        ch["radius"] = fl(16.13e-3 + j * dx)
        return f"charge radius grown through the case wall ({16.13e-3 + j * dx:.6g} m)", ("case", "charge")
    k = rng.choice([3, 4, 5])
    ch["center"][0] = fl(k * dx)
    return f"charge shifted {k} cells sideways into the case wall", ("case", "charge")


def _ov_kalthoff(rng, t, dx, touching):
    pl, pr = _body(t, "plate")["shape"], _body(t, "projectile")["shape"]
    if touching:
        if rng.random() < 0.5:
            pr["lower"][0], pr["upper"][0] = fl(-0.05), fl(0.0)
            return "projectile moved onto the plate's face (upper x = 0)", ("plate", "projectile")
        pl["lower"][0] = fl(-0.0005)
        return "plate grown onto the projectile's face (lower x = -0.0005)", ("plate", "projectile")
    k = rng.choice([3, 4, 6, 8])
    op = rng.randrange(3)
    if op == 0:
        pr["upper"][0] = fl(k * dx)
        return f"projectile grown {k} cells into the plate", ("plate", "projectile")
    if op == 1:
        pr["lower"][0], pr["upper"][0] = fl(-0.0505 + 0.0005 + k * dx), fl(k * dx)
        return f"projectile shifted {k} cells into the plate", ("plate", "projectile")
    pl["lower"][0] = fl(-0.0005 - k * dx)
    return f"plate grown {k} cells into the projectile", ("plate", "projectile")


def _ov_jet(rng, t, dx, touching):
    target, cement, casing = (_body(t, n)["shape"] for n in ("target", "cement", "casing"))
    if touching:
        if rng.random() < 0.5:
            target["length"] = fl(104e-3)
            return "target lengthened onto the cement (top at 104 mm)", ("target", "cement")
        cement["center"][1], cement["length"] = fl(100e-3), fl(19e-3)
        return "cement from the target's top (100 mm) to the casing (119 mm)", ("target", "cement")
    op = rng.randrange(3)
    k = rng.choice([3, 4])
    if op == 0:
        casing["center"][1] = fl(119e-3 - k * dx)
        return f"casing shifted {k} cells into the cement", ("cement", "casing")
    if op == 1:
        cement["length"] = fl(15e-3 + k * dx)
        return f"cement lengthened {k} cells into the casing", ("cement", "casing")
    k = rng.choice([3, 5])
    target["length"] = fl(104e-3 + k * dx)
    return f"target lengthened {k} cells into the cement", ("target", "cement")


def _ov_rod(rng, t, dx, touching):
    rod, billet = _body(t, "rod")["rod"], _body(t, "billet")["shape"]
    if touching:
        if rng.random() < 0.5:
            rod["nose"][1] = fl(49.5e-3)
            return "rod nose on the billet's face (49.5 mm)", ("billet", "rod")
        billet["length"] = fl(50e-3)
        return "billet lengthened to the rod nose (50 mm)", ("billet", "rod")
    k = rng.choice([3, 5, 10])
    if rng.random() < 0.5:
        rod["nose"][1] = fl(49.5e-3 - k * dx)
        return f"rod nose {k} cells inside the billet", ("billet", "rod")
    billet["length"] = fl(50e-3 + k * dx)
    return f"billet lengthened {k} cells into the rod", ("billet", "rod")


def _ov_disks(rng, t, dx, touching):
    a, b = _body(t, "lower_left")["shape"], _body(t, "upper_right")["shape"]
    c = [float(x) for x in a["center"]]
    rsum = float(a["radius"]) + float(b["radius"])
    if touching:
        if rng.random() < 0.5:
            b["center"][0], b["center"][1] = fl(c[0] + rsum), fl(c[1])
            return "disks tangent along x", ("lower_left", "upper_right")
        dist = rsum
    else:
        k = rng.choice([3, 4, 6])
        dist = rsum - k * dx
    off = dist / math.sqrt(2)
    b["center"][0], b["center"][1] = fl(c[0] + off), fl(c[1] + off)
    if touching:
        return "disks tangent along the diagonal", ("lower_left", "upper_right")
    return f"disks overlap by {k} cells along the diagonal", ("lower_left", "upper_right")


SPECIFIC = {"explosive_sandwich_mpm": _ov_sandwich, "exploding_cylinder_pd": _ov_cylinder,
            "pd_kalthoff_winkler": _ov_kalthoff, "jet_casing_sandstone_mpm": _ov_jet, "rod_billet_4130_mpm": _ov_rod,
            "elastic_disks": _ov_disks}


def _shape_bodies(t):
    return [b for b in t["bodies"] if isinstance(b, dict) and isinstance(b.get("shape"), dict)
            and b["shape"].get("type") in ("box", "cylinder", "tube", "sphere")]


def _nested_copy(rng, t, dx):
    """A copy of a body, shrunk by one or two cells on every side, inside it: the overlap is the
    whole copy (at least 3 cells in every direction in which the body extends)."""
    body = rng.choice(_shape_bodies(t))
    copy = _copy(body)
    copy["name"] = "fuzz_copy"
    s = copy["shape"]
    dim3 = _dim3(t)
    m = dx * rng.choice([1, 2])
    if s["type"] == "box":
        for i in range(3 if dim3 else 2):
            lo, up = float(s["lower"][i]), float(s["upper"][i])
            mm = m if up - lo >= 2 * m + 3 * dx else 0.0
            s["lower"][i], s["upper"][i] = fl(lo + mm), fl(up - mm)
    else:
        r = float(s["radius"])
        inner = float(s.get("inner_radius", 0) or 0)
        mm = m if r - inner >= 2 * m + 3 * dx else (dx if r - inner >= 5 * dx else 0.0)
        if s["type"] == "tube":
            s["inner_radius"] = fl(inner + mm)
            s["radius"] = fl(r - mm)
        else:
            s["radius"] = fl(r - mm)
        if "length" in s and s["type"] != "sphere":
            length = float(s["length"])
            ml = m if length >= 2 * m + 3 * dx else 0.0
            ax = "xyz".index(s.get("axis", "z"))
            s["center"][ax] = fl(float(s["center"][ax]) + ml)
            s["length"] = fl(length - 2 * ml)
    for k in ("velocity", "radial_velocity"):
        if k in body:
            copy[k] = body[k]
    t["bodies"].append(copy)
    return f"a copy of {body['name']} shrunk by {m / dx:g} cell(s) inside it (fuzz_copy)", (body["name"], "fuzz_copy")


def _split(rng, t, dx):
    """One body split in two parts that share a face: along the axis of a cylinder (or the x axis
    of a box) or radially (a tube; a cylinder into a core and a tube). The halves keep the material
    and velocity: the same body in two pieces."""
    body = rng.choice(_shape_bodies(t))
    s = body["shape"]
    part = _copy(body)
    part["name"] = "fuzz_part"
    ps = part["shape"]
    on_face = rng.random() < 0.5
    if s["type"] == "box":
        ax = rng.randrange(3 if _dim3(t) else 2)
        lo, up = float(s["lower"][ax]), float(s["upper"][ax])
        x = rng.uniform(lo + 0.3 * (up - lo), lo + 0.7 * (up - lo))
        x = round(x / dx) * dx if on_face else x
        s["upper"][ax] = fl(x)
        ps["lower"][ax] = fl(x)
        where = f"{'xyz'[ax]} = {x:.6g} m"
    elif s["type"] in ("cylinder", "tube") and "length" in s and rng.random() < 0.6:
        ax = "xyz".index(s.get("axis", "z"))
        c, length = float(s["center"][ax]), float(s["length"])
        f = rng.uniform(0.3, 0.7)
        x = c + f * length
        x = round(x / dx) * dx if on_face else x
        s["length"] = fl(x - c)
        ps["center"][ax] = fl(x)
        ps["length"] = fl(c + length - x)
        where = f"{s.get('axis', 'z')} = {x:.6g} m"
    elif s["type"] in ("cylinder", "tube"):
        r, inner = float(s["radius"]), float(s.get("inner_radius", 0) or 0)
        x = rng.uniform(inner + 0.3 * (r - inner), inner + 0.7 * (r - inner))
        x = round(x / dx) * dx if on_face else x
        s["radius"] = fl(x)
        ps["type"], ps["inner_radius"] = "tube", fl(x)
        where = f"radius {x:.6g} m"
    else:  # sphere: a copy beside it, tangent
        return _nested_copy(rng, t, dx)[0], None
    t["bodies"].append(part)
    return f"{body['name']} split in two touching parts at {where} (fuzz_part)", (body["name"], "fuzz_part")


def overlap_deck(rng, text, stem, mut):
    """(deck bytes, descriptions, expectation) for overlap:<stem>. Unmutated: the deck as it is
    (its bodies apart or touching) and no expectation."""
    tree = reduced_tree(text, OVERLAP_DECKS[stem])
    if not mut:
        return dump(tree), [], None
    dx = float(tree["grid"]["cell_size"])
    touching = rng.random() < 0.35
    specific = SPECIFIC.get(stem)
    if specific and rng.random() < 0.7:
        desc, names = specific(rng, tree, dx, touching)
    elif touching:
        desc, names = _split(rng, tree, dx)
        if names is None:  # no face to split on: an overlap instead
            touching = False
            desc, names = _nested_copy(rng, tree, dx)
    else:
        desc, names = _nested_copy(rng, tree, dx)
    if touching:
        return dump(tree), [desc + " (touching)"], {"kind": "touching", "bodies": list(names)}
    return dump(tree), [desc + " (overlap)"], {"kind": "overlap", "bodies": list(names)}


def expectation_class(case, result, stderr, stdout):
    """Reclassify the outcome of an overlap:<stem> case by its expectation (None: unchanged)."""
    exp = case.get("expect")
    if not exp:
        return None
    text = stderr + "\n" + stdout
    a, b = exp["bodies"]
    if exp["kind"] == "overlap":
        if result["class"] in ("ok", "nonfinite_success", "ignored_input"):
            return "overlap_accepted", f"exit 0 although bodies '{a}' and '{b}' overlap ({result['class']})"
        if result["class"] == "rejected" and not (re.search(rf"\b{re.escape(a)}\b", text)
                                                   and re.search(rf"\b{re.escape(b)}\b", text)):
            return "overlap_accepted", (f"refused, but not as an overlap of '{a}' and '{b}' (the deck checks "
                                        f"accepted it): {_error_line(text)[:200]}")
        return None
    if result["exit"] not in (0, None) and result["class"] == "rejected" and "overlap" in text.lower():
        return "touching_refused", f"'{a}' and '{b}' only touch: {_error_line(text)[:200]}"
    return None
