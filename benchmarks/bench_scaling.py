"""Scaling: time per face of the main operations at 10k, 100k, 1M (and 5M) faces.

    python benchmarks/bench_scaling.py            # 10k, 100k, 1M faces (2 min on a quiet machine)
    python benchmarks/bench_scaling.py --quick    # 10k and 100k faces
    python benchmarks/bench_scaling.py --full     # and 5M faces (not timed yet: 10+ min, GiBs)

If the cost grows linearly with the mesh, the time per face stays the same from row to
row: each cell prints microseconds per input face and, beside it, that time over the
10k row's (1.00x is perfectly linear; 2x means a face costs twice as much). Each cell is
the median of a few runs, each on a fresh copy of the mesh (no cached adjacency);
the machine is shared and noisy, so read the ratios, not the seconds.

The input is a torus (every vertex of valence 6, closed), in the order it is generated,
with as many faces as asked to within a fraction of a percent:
* build: ``HalfedgeMesh.from_faces`` (input checks included);
* Loop x1: ``hx.loop_subdivide(mesh)``;
* smooth x10: ``hx.smooth(mesh, 10)``;
* simplify 10%: ``hx.simplify(mesh, faces // 10)``;
* remesh x1: ``hx.remesh(mesh, iterations=1)`` (target length: the mean edge length).

Then the peak memory of building the largest mesh, ours beside ``openmesh.TriMesh``,
each measured in a fresh process: the peak resident set (``VmHWM``) minus what the
process held just before the build (the input arrays, numpy, the libraries), which
Linux lets a process reset by writing 5 to ``/proc/self/clear_refs``.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np

import halfedge_edu as hx
from _common import timed

SIZES = {"quick": [10_000, 100_000], "default": [10_000, 100_000, 1_000_000],
         "full": [10_000, 100_000, 1_000_000, 5_000_000]}


def torus(faces_wanted: int, radii: tuple[float, float] = (1.0, 0.4)) -> tuple[np.ndarray, np.ndarray]:
    """(vertices (n, 3), faces (m, 3)) of a closed torus with about ``faces_wanted`` triangles.

    A grid of ``around x tube`` quads, two triangles each, with ``around / tube`` equal to
    the ratio of the two circumferences so that the triangles are close to right isosceles.
    Faces are counter-clockwise seen from outside; vertices and faces in grid order.
    """
    big, small = radii
    tube = max(3, int(round(np.sqrt(faces_wanted * small / (2 * big)))))
    around = max(3, int(round(faces_wanted / (2 * tube))))
    u = 2 * np.pi * np.arange(around) / around                  # (around,) angle round the hole
    v = 2 * np.pi * np.arange(tube) / tube                      # (tube,) angle round the tube
    ring = big + small * np.cos(v)
    vertices = np.stack([
        np.outer(np.cos(u), ring).ravel(),
        np.outer(np.sin(u), ring).ravel(),
        np.tile(small * np.sin(v), around),
    ], axis=1)                                                  # (around * tube, 3), vertex i * tube + j
    i, j = np.meshgrid(np.arange(around), np.arange(tube), indexing="ij")
    corner = lambda di, dj: (((i + di) % around) * tube + (j + dj) % tube).ravel()  # noqa: E731
    a, b, c, d = corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)
    faces = np.stack([np.stack([a, b, c], axis=1), np.stack([a, c, d], axis=1)], axis=1).reshape(-1, 3)
    return vertices, faces


def median_fresh(repeats: int, algorithm, mesh: hx.HalfedgeMesh) -> float:
    """Median seconds of ``algorithm(copy)`` over ``repeats`` fresh copies (copying is not timed)."""
    return float(np.median([timed(algorithm, mesh.copy())[0] for _ in range(max(1, repeats))]))


def operations(faces: int) -> dict:
    """The timed operations, each a function of a built mesh (build takes the arrays instead)."""
    return {
        "build": None,
        "Loop x1": hx.loop_subdivide,
        "smooth x10": lambda mesh: hx.smooth(mesh, 10),
        "simplify 10%": lambda mesh: hx.simplify(mesh, faces // 10),
        "remesh x1": lambda mesh: hx.remesh(mesh, iterations=1),
    }


#: Operations that take minutes at a million faces, timed fewer times there.
SLOW = {"simplify 10%", "remesh x1"}


def repeats_for(faces: int, name: str) -> int:
    """Median of 5 runs up to ~100k faces; at 1M, 3 (1 for the slow operations); 1 beyond."""
    if faces <= 200_000:
        return 5
    if faces <= 2_000_000:
        return 1 if name in SLOW else 3
    return 1


def time_row(faces_wanted: int) -> tuple[int, dict[str, float]]:
    """(faces, seconds per operation) for a torus of about ``faces_wanted`` faces."""
    vertices, faces = torus(faces_wanted)
    repeats = {name: repeats_for(len(faces), name) for name in operations(0)}
    seconds = {"build": float(np.median([timed(hx.HalfedgeMesh.from_faces, vertices, faces)[0]
                                         for _ in range(repeats["build"])]))}
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    for name, algorithm in operations(len(faces)).items():
        if algorithm is not None:
            seconds[name] = median_fresh(repeats[name], algorithm, mesh)
    return len(faces), seconds


PEAK_SCRIPT = """
import sys
sys.path.insert(0, {here!r})
from bench_scaling import torus
vertices, faces = torus({faces})
{prepare}
with open("/proc/self/clear_refs", "w") as clear:
    clear.write("5")                       # peak resident set := what the process holds now
held = {{line.split(":")[0]: int(line.split()[1]) for line in open("/proc/self/status") if line.startswith("Vm")}}
mesh = {build}
peak = {{line.split(":")[0]: int(line.split()[1]) for line in open("/proc/self/status") if line.startswith("Vm")}}
print(peak["VmHWM"] - held["VmRSS"], peak["VmHWM"])
"""

BUILDERS = {
    "halfedge_edu": ("import halfedge_edu as hx", "hx.HalfedgeMesh.from_faces(vertices, faces)"),
    "openmesh": ("import openmesh", "openmesh.TriMesh(vertices, faces)"),
}


def peak_build_memory_mib(faces: int, library: str) -> tuple[float, float]:
    """(peak MiB above what the process held before the build, peak MiB of the whole process)."""
    prepare, build = BUILDERS[library]
    code = PEAK_SCRIPT.format(here=str(Path(__file__).resolve().parent), faces=faces, prepare=prepare, build=build)
    above, whole = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                  check=True).stdout.split()
    return int(above) / 1024, int(whole) / 1024


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    size = parser.add_mutually_exclusive_group()
    size.add_argument("--quick", action="store_true", help="10k and 100k faces only")
    size.add_argument("--full", action="store_true", help="add the 5M-face row (minutes, ~6 GiB)")
    args = parser.parse_args(argv)
    sizes = SIZES["quick" if args.quick else "full" if args.full else "default"]

    names = list(operations(0))
    print("Scaling: microseconds per input face (ratio to the first row; 1.00x = linear)")
    header = f"{'faces':>10}" + "".join(f"{name:>20}" for name in names) + f"{'runs':>10}"
    print(header)
    print("-" * len(header))
    first = None
    for wanted in sizes:
        faces, seconds = time_row(wanted)
        per_face = {name: seconds[name] / faces for name in names}
        first = first or per_face
        cells = "".join(f"{per_face[name] * 1e6:>12.3f} {per_face[name] / first[name]:>6.2f}x" for name in names)
        runs = "/".join(str(repeats_for(faces, name)) for name in names)
        print(f"{faces:>10,}{cells}{runs:>10}", flush=True)

    largest = sizes[-1]
    print()
    print(f"peak memory while building {largest:,} faces (fresh process each; above the input / whole process):")
    for library in BUILDERS:
        above, whole = peak_build_memory_mib(largest, library)
        print(f"  {library:<14}{above:>8.0f} MiB above the input {whole:>8.0f} MiB in all")


if __name__ == "__main__":
    main()
