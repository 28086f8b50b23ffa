"""Reading OBJ files: our own parser (taught in chapter 01) beside trimesh's, same run.

    python benchmarks/bench_io.py [--repeat 5]

Prints the median of several reads of each bundled mesh for ``hx.read_obj`` (arrays
only), ``hx.load`` (arrays plus the halfedge build) and ``trimesh.load`` (its own OBJ
reader, ``process=False`` so it does no more than read), and their ratio.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import trimesh

import halfedge_edu as hx
from _common import interleaved_medians

DATA = Path(hx.__file__).resolve().parent / "data"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--quick", action="store_true", help="fewer repeats (run_all passes it)")
    options = parser.parse_args()
    repeat = 3 if options.quick else options.repeat

    print(f"OBJ reading, median of {repeat} interleaved rounds (ratio = ours / trimesh.load)")
    print(f"{'mesh':<22}{'faces':>8}{'read_obj':>11}{'hx.load':>11}{'trimesh':>11}{'read ratio':>12}")
    for path in sorted(DATA.glob("*.obj")):
        faces = len(hx.read_obj(path).faces)
        timings = interleaved_medians(repeat, {                  # one of each in turn, per round
            "read_obj": lambda: hx.read_obj(path),
            "load": lambda: hx.load(path),
            "trimesh": lambda: trimesh.load(path, process=False, force="mesh"),
        })
        ours, loaded, peer = (timings[name][0] for name in ("read_obj", "load", "trimesh"))
        print(f"{path.name:<22}{faces:>8}{ours:>10.3f}s{loaded:>10.3f}s{peer:>10.3f}s{ours / peer:>11.2f}x")


if __name__ == "__main__":
    main()
