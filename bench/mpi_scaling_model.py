#!/usr/bin/env python3
"""Scaling model of Ballista's MPM on many MPI ranks (issue 16 item 5; docs/performance.md,
"Several ranks"). A model, not a measurement: it extrapolates what bench/mpi_block_impact.sh
measures on this 2-core machine to 1,000 ranks for the 10^8-particle 3D jet case.

Measured inputs (arguments):
  --rate        particle-steps/s of one rank x one thread (the compute rate of a core)
  --halo-bytes  halo bytes per step sent by one rank of the 4-rank run
  --halo-faces  cell faces (cells^2) of that rank's boundary with other ranks, from the same run
  --ppc         particles per cell (8 in the benchmark: 2 per axis)

Assumptions (written into the output too):
  - RCB subdomains are near-cubes of n = N / P / ppc cells; an interior rank borders others on
    6 faces of n^(2/3) cells^2 each, and exchanges with 26 neighbours (faces, edges, corners);
  - halo bytes scale with the bordering area at the measured bytes per cell^2 (block granularity
    included: a shared block is 8 nodes deep);
  - two halo exchanges per step (the full P2G pass and the MUSL momentum pass);
  - network: 10 GB/s per rank, 2 us per message, allreduce 5 us x log2(P), 12 allreduces per step
    (time step, migration counts, imbalance, failure agreement, block plan, energies);
  - an all-gather of the active-block lists as an upper bound (the code sends them to the
    neighbouring ranks only): every rank receives every rank's list, 8 bytes per block of 512
    nodes; its time at the network bandwidth;
  - the migration's two all-to-alls per step (counts, then particles): log2(P) rounds of one
    latency each (Bruck), plus P counts of 4 bytes;
  - load imbalance: the particles are repartitioned at mpm.rebalance_imbalance = 0.1, so the
    slowest rank carries on average 5 % more than the mean (--imbalance 0.05);
  - compute does not change with P (per-core rate as measured; no cache effects);
  - NOT modelled, because the code does not do it yet: every rank seeds every body and allocates
    the node arrays of the whole grid (10^8 particles need ~46 GB per rank for the seeding alone:
    the 10^8 case needs seeding by region and per-rank grid blocks first), and Zoltan's cost when
    it repartitions.
"""
import argparse, math


def model(N, P, a):
    cells = N / P / a.ppc
    face = cells ** (2.0 / 3.0)
    area = 6.0 * face if P > 1 else 0.0
    halo_bytes = a.halo_bytes / a.halo_faces * area
    messages = 2 * min(26, P - 1)
    t_comp = N / P / a.rate * (1.0 + (a.imbalance if P > 1 else 0.0))
    t_halo = halo_bytes / a.bandwidth + messages * a.latency
    t_reduce = 12 * a.allreduce * math.log2(P) if P > 1 else 0.0
    blocks_per_rank = (cells * (1.0 + 2.0 / cells ** (1.0 / 3.0)) ** 3) / 512.0  # node blocks incl. a layer
    t_gather = (P * blocks_per_rank * 8.0) / a.bandwidth if P > 1 else 0.0
    t_a2a = 2.0 * (math.log2(P) * a.latency + 4.0 * P / a.bandwidth) if P > 1 else 0.0
    t_reduce += t_a2a
    t = t_comp + t_halo + t_reduce + t_gather
    return t, t_comp, t_halo, t_reduce, t_gather, halo_bytes, messages


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rate", type=float, required=True)
    ap.add_argument("--halo-bytes", type=float, required=True)
    ap.add_argument("--halo-faces", type=float, required=True)
    ap.add_argument("--ppc", type=float, default=8.0)
    ap.add_argument("--bandwidth", type=float, default=10e9)
    ap.add_argument("--latency", type=float, default=2e-6)
    ap.add_argument("--allreduce", type=float, default=5e-6)
    ap.add_argument("--imbalance", type=float, default=0.05)
    ap.add_argument("--particles", type=float, default=1e8)
    ap.add_argument("--weak-per-rank", type=float, default=1e5)
    a = ap.parse_args()
    print(f"measured: {a.rate:.3g} particle-steps/s per core; {a.halo_bytes / a.halo_faces:.4g} halo bytes per "
          f"cell^2 of rank boundary per step")
    t1 = a.particles / a.rate
    print(f"\nstrong scaling, {a.particles:.0e} particles (one core: {t1:.1f} s per step)")
    print(f"{'ranks':>6} {'s/step':>9} {'compute':>9} {'halo':>9} {'collect.':>9} {'gather':>9} {'halo MB':>8} "
          f"{'msgs':>5} {'efficiency':>10}")
    for P in (4, 16, 64, 256, 1000):
        t, c, h, r, g, hb, m = model(a.particles, P, a)
        print(f"{P:>6} {t:9.4f} {c:9.4f} {h:9.5f} {r:9.5f} {g:9.5f} {hb / 1e6:8.2f} {m:>5} {t1 / P / t:10.2f}")
    print(f"\nweak scaling, {a.weak_per_rank:.0e} particles per rank")
    print(f"{'ranks':>6} {'s/step':>9} {'halo':>9} {'collect.':>9} {'gather':>9} {'efficiency':>10}")
    base = a.weak_per_rank / a.rate
    for P in (4, 16, 64, 256, 1000):
        t, c, h, r, g, hb, m = model(a.weak_per_rank * P, P, a)
        print(f"{P:>6} {t:9.4f} {h:9.5f} {r:9.5f} {g:9.5f} {base / t:10.2f}")


if __name__ == "__main__":
    main()
