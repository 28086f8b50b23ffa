"""`make bench` names the machine it ran on and says whether its figures may go into the docs."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import _common  # noqa: E402 - benchmarks/ is not a package


def test_the_machine_report_names_cpu_cores_load_and_versions():
    line = _common.machine_report()
    assert line.startswith("machine: ") and "logical cores" in line and "load " in line
    assert _common.cpu_model() in line and "numpy " in line


def test_a_quiet_run_is_fit_for_the_docs_and_a_busy_one_is_said_not_to_be():
    fit, words = _common.fit_for_the_docs(0.1, 0.3, cores=2)
    assert fit and "fit for the docs" in words
    for before, after in ((0.1, 0.6), (0.9, 0.1), (2.0, 2.0)):
        fit, words = _common.fit_for_the_docs(before, after, cores=2)
        assert not fit and "NOT fit" in words, (before, after)
    assert _common.fit_for_the_docs(1.5, 1.5, cores=8)[0]       # a quarter of 8 cores is 2
