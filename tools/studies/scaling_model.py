#!/usr/bin/env python3
"""Communication model of a distributed Talus run (docs/scaling.md), from measured costs.

Inputs measured on the 2-core VM (commands in docs/scaling.md):
  - compute rate per core on the terrain case (talus bench --case terrain --threads 1)
  - halo bytes per rank per step and boundary blocks per rank on the terrain case at dx 2 m
    (mpirun -np 4 talus bench --ranks --case terrain --scale 8 --threads 1; stderr per rank)
Network figures are typical, not measured here: 10 Gb/s Ethernet (TCP) and 100 Gb/s InfiniBand.
"""
import math

RATE_PER_CORE = 3.6e6          # particle-steps/s, terrain case, 1 thread (measured 3.6-3.7e6)
PARALLEL_EFF = 0.9             # threads within a rank (measured 79-98 % at 2 threads)
HALO_BYTES_REF = 310e3         # mean halo bytes sent per rank per step at 4 ranks, dx 2 m
PARTICLES_REF = 119e3          # particles per rank in that run
COLLECTIVES = 16               # latency-bound collectives per step (dt 4, speed, finite, count,
                               # imbalance 2, loads, 2 all-to-all counts, neighbours' blocks,
                               # run: root flag, 2 signal agreements, minima)
NEIGHBOURS = 6                 # halo messages per rank per step
# Per-step outputs in parts (io/output/step_parts.h): each rank sends rank 0 the map cells its
# particles touch, 4 + 32 bytes per material each; rank 0 adds them alone.
CELL_BYTES = 4 + 32 * 2        # two materials' layers
PARTICLES_PER_CELL = 13        # particles per touched map cell per step: the default scene on 2
                               # ranks, rank 1's 33 313 particles sent 91 KB of parts a step
                               # (36 bytes a cell, one layer), against a run without maps
MERGE_NS_PER_CELL = 30         # adding and folding per cell received: assumed, not measured
                               # alone (a copy, 4-8 integer adds and a few maxima)
# Since: cells owned by ranks (OutputObserver::partsByOwner): each rank sends every touched cell
# to the rank owning its row (bands of 8 rows in turn) and adds and folds the rows it owns; rank
# 0 gathers them only for a film frame, a checkpoint and the end. The adding of received cells
# is serial per rank, the folding parallel over its threads (taken here as a third of the 30 ns
# and the rest). A rank's blocks are a range in the tree's order, a compact patch: its cells
# span about sqrt(cells) rows, so it sends to sqrt(cells)/8 + 1 owners (at most every rank),
# after an all-to-all of the byte counts (log2 of the ranks in latency).
ADD_SHARE = 1 / 3
ROWS_PER_OWNER = 8
NETWORKS = {"10 Gb/s Ethernet": (30e-6, 1.25e9), "100 Gb/s InfiniBand": (2e-6, 12.5e9)}


def step(n_total, ranks, threads, alpha, beta):
    n = n_total / ranks
    compute = n / (RATE_PER_CORE * threads * (PARALLEL_EFF if threads > 1 else 1.0))
    # A rank's share of a thin flow is a patch: its boundary grows as the square root of its area.
    halo = HALO_BYTES_REF * math.sqrt(n / PARTICLES_REF)
    halo_t = NEIGHBOURS * alpha + halo / beta
    # The owning blocks next to a rank's (12 bytes each), told by their ranks: latency only.
    gather_t = alpha * math.log2(ranks)
    coll_t = COLLECTIVES * alpha * math.log2(ranks)
    comm = halo_t + gather_t + coll_t
    return compute, comm, halo


def main():
    n_total = 20e6
    print("| network | ranks | threads/rank | particles/rank | compute ms/step | halo KB/rank/step "
          "| communication ms/step | communication share | p-steps/s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for net, (alpha, beta) in NETWORKS.items():
        for ranks in (16, 100):
            for threads in (1, 16):
                c, m, h = step(n_total, ranks, threads, alpha, beta)
                print(f"| {net} | {ranks} | {threads} | {n_total / ranks:,.0f} | {1e3 * c:.2f} | {h / 1e3:.0f} "
                      f"| {1e3 * m:.3f} | {100 * m / (c + m):.1f} % | {n_total / (c + m):.2e} |")
    print()
    print("Weak scaling (1.25 M particles per rank, 16 threads each), 100 Gb/s:")
    alpha, beta = NETWORKS["100 Gb/s InfiniBand"]
    for ranks in (1, 4, 16, 64, 100, 400):
        c, m, _ = step(1.25e6 * ranks, ranks, 16, alpha, beta) if ranks > 1 else (1.25e6 / (RATE_PER_CORE * 16 * PARALLEL_EFF), 0, 0)
        print(f"  {ranks:4d} ranks: step {1e3 * (c + m):.2f} ms, efficiency {100 * c / (c + m):.1f} %")
    print()
    ranks, threads = 100, 16
    print(f"Per-step outputs of `talus run` in parts (20 M particles, {ranks} ranks of {threads} threads):")
    cells = n_total / PARTICLES_PER_CELL
    for net, (alpha, beta) in NETWORKS.items():
        c, _, _ = step(n_total, ranks, threads, alpha, beta)
        recv = cells * CELL_BYTES / beta
        merge = cells * MERGE_NS_PER_CELL * 1e-9
        print(f"  {net}, all to rank 0 (before): {cells * CELL_BYTES / 1e6:.1f} MB of parts per step into rank 0: "
              f"{1e3 * recv:.2f} ms, its adding {1e3 * merge:.2f} ms, against the engine's {1e3 * c:.2f} ms step: "
              f"+{100 * (recv + merge) / c:.0f} %")
        own = cells / ranks
        messages = min(ranks, math.ceil(math.sqrt(own) / ROWS_PER_OWNER) + 1)
        latency = (messages + math.log2(ranks)) * alpha  # and the all-to-all of the byte counts
        wire = own * CELL_BYTES / beta
        add = own * MERGE_NS_PER_CELL * 1e-9 * (ADD_SHARE + (1 - ADD_SHARE) / (threads * PARALLEL_EFF))
        total = latency + wire + add
        print(f"  {net}, cells owned by ranks: {own * CELL_BYTES / 1e6:.2f} MB per rank per step, "
              f"{messages} messages {1e3 * latency:.2f} ms + bytes {1e3 * wire:.3f} ms + adding and folding "
              f"{1e3 * add:.3f} ms = {1e3 * total:.2f} ms: +{100 * total / c:.0f} %")

if __name__ == "__main__":
    main()
