"""Local operations are constant work: flip, split and collapse on a small and a huge mesh.

    python benchmarks/bench_ops.py            # 1,280 vs 1,310,720 faces; the bunny run
    python benchmarks/bench_ops.py --quick    # 1,280 vs 81,920 faces; fewer operations

Two promises are checked, and the script exits non-zero if one fails:

1. Per-operation cost on a 1.3M-face mesh is within 2x of the same operation on a
   1k-face mesh (icospheres of 20 * 4**3 and 20 * 4**8 faces). Each operation is
   timed alone, on random edges where it is allowed, including the check it makes
   before acting; the table shows the median in microseconds (so the rare O(n) array
   growth when ``add_*`` runs out of spare room, doubling the capacity, does not
   count; the bunny run below includes it). Operations run in
   batches on fresh copies, so the small mesh is never used up. The "logged" rows
   pass ``log=OperationLog()``: that is what a stepper pays, and what the plain
   operation does not.
2. 10,000 random operations (flip, split or collapse on a random edge, each checked
   with ``can_*`` first; refused attempts do not count) plus a final ``validate()``
   on the Stanford bunny (69,451 faces) take under 2 seconds.

The machine may be shared and noisy: read the ratios, and rerun if one is close.
"""

from __future__ import annotations

import argparse
import sys
import time
import timeit

import numpy as np

import halfedge_edu as hx
from halfedge_edu.data import sample
from halfedge_edu.core.ops import (
    OperationLog, can_collapse, can_flip, can_split, collapse, flip, split,
)
from halfedge_edu.core.ops.log import Writer

OPERATIONS = {"flip": (can_flip, flip), "split": (can_split, split), "collapse": (can_collapse, collapse)}


def icosphere(level: int) -> hx.HalfedgeMesh:
    """A unit icosphere with 20 * 4**level faces."""
    import trimesh

    sphere = trimesh.creation.icosphere(subdivisions=level)
    return hx.HalfedgeMesh.from_faces(np.asarray(sphere.vertices), np.asarray(sphere.faces))


def median_microseconds(mesh: hx.HalfedgeMesh, name: str, n_ops: int, batch: int, seed: int, logged: bool) -> float:
    """Median time of one operation ``name`` on random allowed edges, in microseconds."""
    can, act = OPERATIONS[name]
    rng = np.random.default_rng(seed)
    log = OperationLog() if logged else None
    times = []
    while len(times) < n_ops:
        work, in_batch = mesh.copy(), 0  # a fresh copy for every batch
        for e in rng.integers(work.n_edge_slots, size=20 * batch).tolist():
            if in_batch == batch:
                break
            if work._edge_deleted[e] or not can(work, e):
                continue
            start = time.perf_counter()
            act(work, e, log=log)
            times.append(time.perf_counter() - start)
            in_batch += 1
    return 1e6 * float(np.median(times[:n_ops]))


def writer_overhead_ns(repeats: int = 200_000) -> tuple[float, float]:
    """Nanoseconds for one ``Writer.link`` call and for the same two array writes inline.

    Without a log, the operations still write through the plain ``Writer`` (one code
    path for both forms); this is the whole price of that choice.
    """
    mesh = icosphere(1)
    writer, next_, prev = Writer(mesh), mesh._halfedge_next, mesh._halfedge_prev

    def inline():
        next_[3] = 5
        prev[5] = 3

    through_writer = min(timeit.repeat(lambda: writer.link(3, 5), number=repeats, repeat=3)) / repeats
    direct = min(timeit.repeat(inline, number=repeats, repeat=3)) / repeats
    return 1e9 * through_writer, 1e9 * direct


def random_operations(mesh: hx.HalfedgeMesh, n_ops: int, seed: int) -> tuple[float, dict]:
    """Seconds for ``n_ops`` random allowed operations plus a final ``validate()``."""
    rng = np.random.default_rng(seed)
    kinds = ["flip", "split", "collapse"]
    done = {"flip": 0, "split": 0, "collapse": 0, "refused": 0}
    picks = rng.random(4 * n_ops).tolist()
    which = rng.integers(3, size=4 * n_ops).tolist()
    start = time.perf_counter()
    count = 0
    for pick, kind in zip(picks, which):
        e = int(pick * mesh.n_edge_slots)
        if mesh._edge_deleted[e]:
            continue
        name = kinds[kind]
        can, act = OPERATIONS[name]
        if can(mesh, e):
            act(mesh, e)
            done[name] += 1
            count += 1
            if count == n_ops:
                break
        else:
            done["refused"] += 1
    mesh.validate()
    return time.perf_counter() - start, done


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a smaller big mesh and fewer operations")
    args = parser.parse_args()
    big_level = 6 if args.quick else 8
    n_ops = 500 if args.quick else 2000
    n_random = 2000 if args.quick else 10_000

    small = icosphere(3)
    started = time.perf_counter()
    big = icosphere(big_level)
    print(f"built the big icosphere ({big.n_faces:,} faces) in {time.perf_counter() - started:.1f} s")

    ok = True
    print(f"\nmedian microseconds per operation ({n_ops} operations each, check included)")
    small_label, big_label = f"{small.n_faces:,} faces", f"{big.n_faces:,} faces"
    print(f"| {'operation':<17} | {small_label:>11} | {big_label:>15} | ratio |")
    print(f"|{'-' * 19}|{'-' * 13}|{'-' * 17}|-------|")
    for logged in (False, True):
        for name in OPERATIONS:
            small_us = median_microseconds(small, name, n_ops, 50, seed=1, logged=logged)
            big_us = median_microseconds(big, name, n_ops, 50, seed=1, logged=logged)
            ratio = big_us / small_us
            label = f"{name} (logged)" if logged else name
            print(f"| {label:<17} | {small_us:11.1f} | {big_us:15.1f} | {ratio:5.2f} |")
            ok &= ratio < 2.0
    print("per-operation cost within 2x of the small mesh:", "PASS" if ok else "FAIL")
    through_writer, direct = writer_overhead_ns()
    print(
        f"without a log no log object is built; a write through the plain Writer costs "
        f"{through_writer:.0f} ns against {direct:.0f} ns inline (a flip makes about 20 writer calls)"
    )

    bunny = sample("bunny")
    seconds, done = random_operations(bunny, n_random, seed=2)
    within = seconds < 2.0 * n_random / 10_000
    print(
        f"\n{n_random:,} random operations + validate() on the bunny ({bunny.n_faces:,} faces after): "
        f"{seconds:.2f} s ({done['flip']} flips, {done['split']} splits, {done['collapse']} collapses; "
        f"{done['refused']} refused attempts not counted): {'PASS' if within else 'FAIL'} (limit 2 s per 10,000)"
    )
    return 0 if ok and within else 1


if __name__ == "__main__":
    sys.exit(main())
