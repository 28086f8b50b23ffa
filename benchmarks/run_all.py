"""Run every benchmark script in this folder, one after another, each in its own process.

    python benchmarks/run_all.py            # full sizes
    python benchmarks/run_all.py --quick    # smaller sizes, where a script supports it

Each ``bench_*.py`` prints its own table with the peers beside our figures. Separate
processes keep one benchmark's memory and caches from colouring the next.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path


def main() -> int:
    here = Path(__file__).resolve().parent
    extra = sys.argv[1:]
    failures = 0
    for script in sorted(here.glob("bench_*.py")):
        print(f"\n=== {script.name} ===", flush=True)
        result = subprocess.run([sys.executable, str(script), *extra])
        if result.returncode != 0:
            print(f"{script.name} failed with exit code {result.returncode}")
            failures += 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
