#!/usr/bin/env python3
"""Work per particle-step of each MPM kernel, counted from the machine code that runs.

No hardware counters are exposed to `perf stat` on these machines, so the counts come from
valgrind: callgrind with --dump-instr=yes gives how often every instruction of the block bench
executed, and its cache simulation (--cache-sim=yes) the last-level misses of each function. Each
executed instruction is looked up in `objdump -d` of the same binary and its floating-point work
counted (a scalar add, subtract, multiply, divide or square root 1 flop, a fused multiply-add 2,
times 2 or 4 for 128- or 256-bit packed forms). Functions are grouped into the kernels of the
step by name; code inlined into a kernel counts in it.

Per kernel and particle-step it reports: instructions, flops, bytes from memory (last-level misses
x 64 B: reads, and for writes the allocation and the write-back), and the share of the step's time from `perf record` (software
clock). The simulated last level is this machine's L3 (32 MiB, 16-way; valgrind's own guess of
the VM's cache is 256 MiB). docs/performance.md ("Roofline") turns these and bench/machine_bounds_bench into bounds.

  /usr/bin/python3 bench/roofline_counts.py --bench build/bench/mpm_block_impact_bench \\
      --filter 'BM_BlockImpact/linear/100000/1/' --out out/roofline_linear

Other steps through `ballista run` of a deck (--target, --deck): `pd` (the peridynamic step),
`mpm-deck` (MPM with another material, e.g. Johnson-Cook in Karamelo's Taylor bar) and `otm`. Their
native rate is particles x S / (t(W + S) - t(W)) from two runs of W and W + S steps (--warm-steps,
--native-steps), so the setup cancels. valgrind 3.19 does not decode AVX-512: on a machine that has
it, count a build configured with -DBALLISTA_NATIVE=OFF -DCMAKE_CXX_FLAGS=-march=x86-64-v3 and give
the same binary as --ballista, so that the counts, the shares and the rate are of one build.
"""
import argparse
import collections
import json
import os
import re
import shutil
import subprocess
import time

LIBM = r"^(__ieee754_|__)?(pow|exp|expm1|log|log1p|hypot|cbrt|sin|cos|atan2?)(_fma)?(@.*)?$"

# Kernels of the step, matched on the demangled function name (first match wins). Inlined code
# belongs to the function it was inlined into.
KERNELS = [
    ("stable step", r"max_signal_speed|stable_dt|wave_speed"),
    ("stress update", r"MaterialAdapter|polar_rotation|reorthogonalise|j2_return|J2Plasticity|JohnsonCook|update_stress|"
                      r"midpoint_strain_increment|remap_if_distorted|update_in_lanes|j2_|failure_update|Geomodel|geo_"),
    # The C library's transcendental functions (Johnson-Cook's powers, the geomodel's exponentials,
    # the LME shape functions' exponentials): a kernel of their own, so that their cost shows.
    ("libm (pow, exp, log)", LIBM),
    ("P2G", r"particles_to_grid"),
    ("G2P", r"grid_to_particles|deterministic_sum"),
    # The shape functions of a point, computed in P2G, G2P and the MUSL pass alike when not inlined.
    ("stencils (P2G, G2P, MUSL)", r"_stencil<|stencil_of"),
    ("grid zeroing", r"memset"),
    # finish_point (L, x, F and volume of a point) runs in the MUSL gradient pass (in G2P with usl).
    ("MUSL gradient + F, x", r"velocity_gradient_from_grid|finish_point"),
    ("grid update", r"update_grid|apply_velocity_bcs|velocity_from_momentum|apply_contact|for_each_active_node"),
    ("bucketing, active blocks", r"build_slabs|mark_active_blocks|ActiveBlocks|stencil_reach"),
    ("sort", r"sort_by_cell|permute|FieldStore::|memmove|memcpy"),
    ("energies, checks", r"energies|handle_exits|kinetic_energy|record_min"),
]
FLOP_RE = re.compile(r"^v?(add|sub|mul|div|sqrt|fmadd\d*|fmsub\d*|fnmadd\d*|fnmsub\d*)(s|p)d$")


# The peridynamic step (bench/pd_cube_bench.yaml through `ballista run`): the bond pass (forces and
# damage of every bond), the velocity-Verlet update of the points, contact and the stable step.
PD_KERNELS = [
    ("stable step", r"PdSolver::stable_dt|max_signal_speed|wave_speed"),
    ("bond pass", r"bond_pass|BondPass|bond_force"),
    ("contact", r"contact|Contact"),
    ("gas", r"gas_pass|GasPass"),
    ("update of the points", r"PdSolver::advance|PdSolver::compute_forces|PdSolver::step|for_each"),
    ("grid zeroing", r"memset"),
]
# The OTM step (`ballista run` of an OTM deck): the supports (which nodes each point sees), the local max-entropy shape functions, the assembly of nodal mass and forces, the
# stress update, the stable step (the Gershgorin bound over the nodes' rows) and the node and point
# update (the rest of the step).
OTM_KERNELS = [
    ("stable step", r"OtmSolver::stable_dt|node_bounds|max_signal_speed|wave_speed"),
    ("supports (neighbour search)", r"build_supports|build_influences|build_current_supports|refresh_supports"),
    ("LME shape functions", r"lme_|otm::\(anonymous namespace\)::(evaluate|solve)"),
    ("libm (pow, exp, log)", LIBM),
    ("stress update", KERNELS[1][1]),
    ("assembly (mass, forces)", r"OtmSolver::assemble"),
    ("contact, light nodes, faces", r"contact_node_forces|light_nodes|apply_face_conditions"),
    ("grid zeroing", r"memset"),
    ("node and point update", r"OtmSolver::step_local|for_each"),
]
TARGETS = {
    # toggles (what callgrind counts), the function called once per step (the whole name: its
    # lambdas' names contain it too), the kernels
    "mpm": (["ballista::MpmSolver::step(double)", "ballista::MpmSolver::stable_dt()"],
            r"^ballista::MpmSolver::step_local\(double\)$", KERNELS),
    "pd": (["ballista::PdSolver::step(double)", "ballista::PdSolver::stable_dt()"],
           r"^ballista::PdSolver::advance\(double\)$", PD_KERNELS),
    # MPM through `ballista run` of a deck (--deck): another material than the bench's J2 block
    "mpm-deck": (["ballista::MpmSolver::step(double)", "ballista::MpmSolver::stable_dt()"],
                 r"^ballista::MpmSolver::step_local\(double\)$", KERNELS),
    "otm": (["ballista::OtmSolver::step(double)", "ballista::OtmSolver::stable_dt()"],
            r"^ballista::OtmSolver::step_local\(double\)$", OTM_KERNELS),
}


def kernel_of(name, kernels=None):
    for k, pat in kernels or KERNELS:
        if re.search(pat, name):
            return k
    return "other"


def flops_of(mnemonic, operands):
    m = FLOP_RE.match(mnemonic)
    if not m:
        return 0
    per = 2 if "fm" in m.group(1) or "fnm" in m.group(1) else 1
    if m.group(2) == "s":
        return per
    return per * (4 if "%ymm" in operands else 2)


def disassemble(binary):
    """address -> (mnemonic, operands) and symbol -> address of the binary's text."""
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", binary], stdout=subprocess.PIPE, text=True,
                         check=True).stdout
    insn, syms = {}, {}
    for line in out.splitlines():
        s = re.match(r"^([0-9a-f]+) <(.+)>:$", line)
        if s:
            syms[s.group(2)] = int(s.group(1), 16)
            continue
        i = re.match(r"^\s+([0-9a-f]+):\s+(\S+)\s*(.*)$", line)
        if i:
            insn[int(i.group(1), 16)] = (i.group(2), i.group(3))
    return insn, syms


def compressed_name(line, kind, table):
    """callgrind's name compression: `kind=(id) name` (or `ckind=...`, the callee's) defines id,
    `kind=(id)` refers to it. (key, name) of such a line, else None."""
    m = re.match(rf"^(c?{kind})=\((\d+)\)(?: (.*))?$", line)
    if not m:
        return None
    key, ident, name = m.groups()
    if name is not None:
        table[ident] = name
    return key, table[ident]


def parse_callgrind(path, step_fn):
    """Self cost per function and address (Ir), per function (every event), and the calls of the
    step function and of the sort."""
    names = {}
    objects = {}  # ob id -> path
    fn_object = {}  # fn -> path of the object it is in
    ob = None
    events = []
    cost = collections.defaultdict(collections.Counter)  # fn -> addr -> Ir
    per_fn = collections.defaultdict(collections.Counter)  # fn -> event -> count
    fn = None
    last_addr = 0
    skip_next = False
    step_calls = 0
    sort_calls = 0
    cfn = None
    for line in open(path):
        line = line.rstrip("\n")
        if line.startswith("events:"):
            events = line.split()[1:]
            continue
        o = compressed_name(line, "ob", objects)
        if o:
            if o[0] == "ob":
                ob = o[1]
            continue
        m = compressed_name(line, "fn", names)
        if m:
            if m[0] == "fn":
                fn = m[1]
                fn_object.setdefault(fn, ob)
            else:
                cfn = m[1]
            continue
        if line.startswith("calls="):
            if cfn and re.search(step_fn, cfn):
                step_calls += int(line.split("=")[1].split()[0])
            if cfn and re.search(r"^ballista::MpmSolver::sort_by_cell\(\)$", cfn):
                sort_calls += int(line.split("=")[1].split()[0])
            skip_next = True
            continue
        if not line or not (line[0] in "+-*0123456789"):
            continue
        parts = line.split()
        pos = parts[0]
        if pos == "*":
            addr = last_addr
        elif pos[0] in "+-":
            addr = last_addr + int(pos, 0)
        else:
            addr = int(pos, 0)
        last_addr = addr
        # positions: instr line -> the second field is the line; the costs follow.
        values = [int(v) for v in parts[2:]]
        if skip_next:
            skip_next = False
            continue
        vec = dict(zip(events, values))
        cost[fn][addr] += vec.get("Ir", 0)
        per_fn[fn].update(vec)
    return cost, per_fn, step_calls, sort_calls, fn_object


def perf_shares(args, kernels):
    """Share of samples per kernel from perf record (software cpu-clock) of a native run."""
    data = args.out + "/perf.data"
    subprocess.run(["perf", "record", "-e", "cpu-clock", "-F", "2000", "-o", data, "--"] + workload(args, None, True),
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True,
                   env=dict(os.environ, OMP_NUM_THREADS=str(args.threads)))
    rep = subprocess.run(["perf", "report", "-i", data, "--stdio", "--no-children", "--sort", "symbol",
                          "--percent-limit", "0"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout
    shares = collections.Counter()
    for line in rep.splitlines():
        m = re.match(r"^\s+([\d.]+)%\s+\[\.\]\s+(.*)$", line)
        if m:
            name = re.sub(r"\s{2,}.*$", "", m.group(2))  # without the report's trailing columns
            shares[kernel_of(name, kernels)] += float(m.group(1))
    # The samples also cover the bench's setup (seeding, deck), which lands in "other"; the step's
    # own "other" is ~0.2 % of its instructions (callgrind), so the kernels' shares are taken
    # relative to their sum.
    inside = sum(v for k, v in shares.items() if k != "other")
    return collections.Counter({k: 100.0 * v / inside for k, v in shares.items() if k != "other"})


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", default="build/bench/mpm_block_impact_bench")
    ap.add_argument("--filter", default="BM_BlockImpact/linear/100000/1/")
    ap.add_argument("--particles", type=float, default=None, help="particle count (default: from the bench)")
    ap.add_argument("--out", default="out/roofline")
    ap.add_argument("--no-perf", action="store_true")
    ap.add_argument("--bounds", help="bench/machine_bounds_bench --benchmark_format=json output: adds the roofline")
    ap.add_argument("--threads", type=int, default=1, help="threads of the filtered benchmark (for --bounds)")
    ap.add_argument("--target", choices=sorted(TARGETS), default="mpm",
                    help="mpm: the block bench (--bench, --filter); pd, mpm-deck, otm: `ballista run` of --deck")
    ap.add_argument("--ballista", default="build/ballista")
    ap.add_argument("--deck", default="bench/pd_cube_bench.yaml")
    ap.add_argument("--steps", type=int, default=None, help="deck targets: steps counted under valgrind")
    ap.add_argument("--native-steps", type=int, default=None,
                    help="mpm-deck, otm: steady steps of the native runs (perf shares and the rate, which is "
                         "particles x S / (t(W + S) - t(W)) with W = --warm-steps, so the setup cancels)")
    ap.add_argument("--warm-steps", type=int, default=20)
    ap.add_argument("--sort-every", type=int, default=20, help="the bench deck's mpm.sort_every")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    cg = a.out + "/callgrind.out"
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
    toggles, step_fn, kernels = TARGETS[a.target]
    binary = a.bench if a.target == "mpm" else a.ballista
    # The counts are addresses of the binary that ran: a copy of it is kept beside them, so that a
    # rebuild between recording and reading cannot mismatch them.
    kept = os.path.join(a.out, "counted_binary")
    if not os.path.exists(cg):
        shutil.copy2(binary, kept)
        run = subprocess.run(["valgrind", "--tool=callgrind", "--dump-instr=yes", "--cache-sim=yes", "--LL=33554432,16,64"]
                             + [f"--toggle-collect={t}" for t in toggles]
                             + [f"--callgrind-out-file={cg}"] + workload(a, a.steps),
                             stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, env=env, check=True)
        if a.target == "mpm":
            open(a.out + "/bench.json", "w").write(run.stdout)
    if a.target == "mpm":
        bench = json.load(open(a.out + "/bench.json"))
        particles = a.particles or bench["benchmarks"][0]["particles"]  # the same block every repetition
    else:
        particles = a.particles or json.load(open(a.out + "/run/summary.json"))["statistics"]["particles_seeded"]
    cost, per_fn, steps, sorts, fn_object = parse_callgrind(cg, step_fn)
    if steps == 0:
        raise SystemExit(f"no call of {step_fn} found in {cg}")
    # Each object's code (the executable from its kept copy, the C math library where the step
    # calls it) and its load base under valgrind: the most common difference between where a
    # function's lowest executed address lies and where objdump puts its symbol.
    exe = os.path.realpath(binary)
    code = {}  # object path -> (insn, base)
    for path in sorted({p for p in fn_object.values() if p}):
        if os.path.realpath(path) == exe:
            insn, syms = disassemble(kept if os.path.exists(kept) else binary)
        elif re.search(r"/libm[.-]", path) and os.path.exists(path):
            insn, syms = disassemble(path)
        else:
            continue
        diffs = collections.Counter()
        for fn, addrs in cost.items():
            at = syms.get(fn.split("'")[0])  # callgrind marks recursion cycles with 'N
            if fn_object.get(fn) == path and at is not None:
                diffs[min(addrs) - at] += 1
        code[path] = (insn, diffs.most_common(1)[0][0] if diffs else 0)
    base = code.get(next((p for p in code if os.path.realpath(p) == exe), None), (None, 0))[1]
    ps = particles * steps
    rows = collections.defaultdict(collections.Counter)
    unknown = 0
    for fn, addrs in cost.items():
        k = kernel_of(fn, kernels)
        insn, fn_base = code.get(fn_object.get(fn), ({}, 0))
        for addr, ir in addrs.items():
            ins = insn.get(addr - fn_base)
            if ins is None:
                unknown += ir
                continue
            rows[k]["flops"] += ir * flops_of(*ins)
        miss = per_fn[fn]
        rows[k]["Ir"] += miss.get("Ir", 0)
        # Last-level read misses and write misses of data, 64-byte lines; a line missed on a write
        # is read (write-allocate) and later written back: twice.
        rows[k]["bytes"] += 64 * (miss.get("DLmr", 0) + 2 * miss.get("DLmw", 0))
    shares = {} if a.no_perf else perf_shares(a, kernels)
    total_ir = sum(r["Ir"] for r in rows.values())
    name = a.filter if a.target == "mpm" else a.deck
    result = {"workload": name, "particles": particles, "steps": steps, "sorts": sorts, "load_base": hex(base),
              "unmatched_instruction_share": unknown / max(total_ir, 1), "kernels": {}}
    order = [k for k, _ in kernels] + ["other"]
    print(f"{name}: {particles:.0f} particles x {steps} steps (valgrind); per particle-step:")
    print(f"{'kernel':26s} {'instr':>8s} {'flops':>8s} {'bytes':>8s} {'flop/B':>7s} {'time %':>7s}")
    # Each solver the bench builds sorts at its first step: far more often than the steady state's
    # once every --sort-every steps, to which the sort's counts are scaled.
    if sorts and "sort" in rows:
        scale = steps / sorts / a.sort_every
        rows["sort"] = collections.Counter({q: v * scale for q, v in rows["sort"].items()})
    for k in order:
        r = rows.get(k)
        if not r:
            continue
        d = {"instructions": r["Ir"] / ps, "flops": r["flops"] / ps, "bytes": r["bytes"] / ps,
             "time_share": shares.get(k, 0.0) / 100.0 if shares else None}
        result["kernels"][k] = d
        ai = d["flops"] / d["bytes"] if d["bytes"] else float("inf")
        sh = f"{100 * d['time_share']:6.1f}" if d["time_share"] is not None else "     -"
        print(f"{k:26s} {d['instructions']:8.0f} {d['flops']:8.0f} {d['bytes']:8.0f} {ai:7.2f} {sh}")
    tot = {q: sum(v[q] for v in result["kernels"].values()) for q in ("instructions", "flops", "bytes")}
    result["total"] = tot
    print(f"{'total':26s} {tot['instructions']:8.0f} {tot['flops']:8.0f} {tot['bytes']:8.0f}")
    if a.bounds and shares:
        result["roofline"] = roofline(result, a)
    json.dump(result, open(a.out + "/roofline_counts.json", "w"), indent=1)


def workload(a, steps, native=False):
    """The command that runs the counted steps: the MPM block bench (three repetitions under
    valgrind, a timed run natively) or `ballista run` of a deck (peridynamics) for `steps` steps
    (the deck's own count natively)."""
    if a.target == "mpm":
        if native:
            return [a.bench, f"--benchmark_filter={a.filter}", "--benchmark_min_time=3"]
        return [a.bench, f"--benchmark_filter={a.filter}", "--benchmark_min_time=0.01", "--benchmark_repetitions=3",
                "--benchmark_format=json"]
    cmd = [a.ballista, "run", a.deck, "-o", a.out + ("/native" if native else "/run"), "-q", "--no-plots",
           "--overwrite", "--threads", str(a.threads if native else 1)]
    if native and steps is None and a.target != "pd" and a.native_steps:
        steps = a.warm_steps + a.native_steps  # the perf run: the rate's longer run
    return cmd + (["--set", f"simulation.max_steps={steps}"] if steps else [])


def measured_rate(a):
    """Particle-steps per second of the workload on this machine, natively."""
    if a.target in ("mpm-deck", "otm"):
        # Two runs, W and W + S steps: the difference is S steady steps without the setup.
        walls = []
        for steps in (a.warm_steps, a.warm_steps + a.native_steps):
            cmd = workload(a, steps, True)
            t0 = time.perf_counter()
            subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True,
                           env=dict(os.environ, OMP_WAIT_POLICY="passive"))
            walls.append(time.perf_counter() - t0)
        particles = json.load(open(a.out + "/native/summary.json"))["statistics"]["particles_seeded"]
        return particles * a.native_steps / (walls[1] - walls[0])
    if a.target == "pd":
        subprocess.run(workload(a, None, True), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        # The run's own rate: its steps' wall time, without the setup (bond families).
        return json.load(open(a.out + "/native/summary.json"))["statistics"]["particle_steps_per_second"]
    out = subprocess.run([a.bench, f"--benchmark_filter={a.filter}", "--benchmark_min_time=3",
                          "--benchmark_format=json"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                         check=True).stdout
    return json.loads(out)["benchmarks"][0]["particle_steps_per_second"]


def roofline(result, a):
    """Each kernel against the machine's bounds (bench/machine_bounds_bench --benchmark_format=json
    in --bounds, the same thread count as the filter): time per particle-step from the measured
    rate and the kernel's share, the time its bytes take at the triad bandwidth and its flops at
    the scalar and the 4-wide FMA peaks, and the instructions per cycle it achieves (the clock from
    the scalar FMA peak: 2 FMA pipes x 2 flops per cycle)."""
    threads = a.threads
    b = {x["name"].split("/min_time")[0]: x for x in json.load(open(a.bounds))["benchmarks"]}
    bw = b[f"BM_StreamTriad/{threads}/real_time"]["bytes_per_second"] if f"BM_StreamTriad/{threads}/real_time" in b \
        else b[f"BM_StreamTriad/{threads}"]["bytes_per_second"]
    pick = lambda name: next(v["flops_per_second"] for k, v in b.items() if k.startswith(f"BM_FmaPeak/{name}/{threads}"))
    scalar, vector = pick("scalar"), pick("avx2")
    clock = scalar / threads / 4.0
    rate = measured_rate(a)
    step = 1.0 / rate * threads  # s per particle-step on one thread
    rows = {}
    print(f"\nroofline ({threads} thread(s)): {rate / 1e6:.2f} M particle-steps/s; triad {bw / 1e9:.1f} GB/s, "
          f"FMA peak scalar {scalar / 1e9:.1f} / 4-wide {vector / 1e9:.1f} GFLOP/s, clock {clock / 1e9:.2f} GHz")
    print(f"{'kernel':26s} {'ns':>6s} {'mem ns':>7s} {'fp ns':>6s} {'fp4 ns':>7s} {'IPC':>5s}")
    for k, d in result["kernels"].items():
        if d["time_share"] is None:
            continue
        t = d["time_share"] * step
        r = {"ns": 1e9 * t, "memory_bound_ns": 1e9 * d["bytes"] / (bw / threads),
             "scalar_flop_bound_ns": 1e9 * d["flops"] / (scalar / threads),
             "vector_flop_bound_ns": 1e9 * d["flops"] / (vector / threads),
             "ipc": d["instructions"] / (t * clock) if t > 0 else None}
        rows[k] = r
        ipc = f"{r['ipc']:5.2f}" if r["ipc"] else "    -"
        print(f"{k:26s} {r['ns']:6.0f} {r['memory_bound_ns']:7.0f} {r['scalar_flop_bound_ns']:6.0f} "
              f"{r['vector_flop_bound_ns']:7.0f} {ipc}")
    return {"rate": rate, "triad_bytes_per_second": bw, "scalar_flops_per_second": scalar,
            "vector_flops_per_second": vector, "clock_hz": clock, "kernels": rows}


if __name__ == "__main__":
    main()
