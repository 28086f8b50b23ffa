"""Run every benchmark script in this folder, one after another, each in its own process.

    python benchmarks/run_all.py            # full sizes
    python benchmarks/run_all.py --quick    # smaller sizes, where a script supports it

Each ``bench_*.py`` prints its own table with the peers beside our figures. Separate
processes keep one benchmark's memory and caches from colouring the next.

The run starts with the machine it is on (CPU, cores, load) and ends with the load after
it and whether the figures may go into the docs: only a run on a quiet machine (1-minute
load below a quarter of the cores before and after, ``_common.fit_for_the_docs``) may.
The exit code is 0 either way unless a script failed; a busy run is said, not hidden.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import fit_for_the_docs, load_average, machine_report  # noqa: E402 - after the path


def main() -> int:
    here = Path(__file__).resolve().parent
    extra = sys.argv[1:]
    print(machine_report(), flush=True)
    load_before = load_average()[0]
    failures = 0
    for script in sorted(here.glob("bench_*.py")):
        print(f"\n=== {script.name} ===", flush=True)
        result = subprocess.run([sys.executable, str(script), *extra])
        if result.returncode != 0:
            print(f"{script.name} failed with exit code {result.returncode}")
            failures += 1
    print()
    print(machine_report())
    print(fit_for_the_docs(load_before, load_average()[0])[1])
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
