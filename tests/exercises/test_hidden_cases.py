"""Hidden cases: every graded check, given a seed, runs only cases made from that seed.

The grader passes ``seed=`` so that a learner cannot fit an answer to the cases the
chapter's check cell shows. These tests pin the contract: keyword-only ``seed``, at
least three hidden cases named "hidden case k: ...", the same cases for the same seed,
``CheckResult.total``, the solution edition passing them for several seeds, an answer
fitted to the public cases failing them, and every call of learner code going through
``harness.run`` (the grader's judge hands the check a proxy, not a real function).
"""

from __future__ import annotations

import inspect
import types

import pytest

from halfedge_edu.exercises import check_fan
from halfedge_edu.exercises.grading import EXERCISES, check_function

from .chapter_solutions import solution_functions

SEEDS = (0, 1, 2, 7, 2026)
CHECKS = sorted({exercise.check for exercise in EXERCISES})


@pytest.mark.parametrize("check_name", CHECKS)
def test_every_graded_check_takes_a_keyword_only_seed_that_defaults_to_the_public_cases(check_name):
    check = check_function(next(e for e in EXERCISES if e.check == check_name))
    seed = inspect.signature(check).parameters["seed"]
    assert seed.kind is inspect.Parameter.KEYWORD_ONLY
    assert seed.default is None


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda exercise: exercise.name)
def test_the_solution_edition_passes_the_public_cases_with_the_total_counted(exercise):
    result = check_function(exercise)(*solution_functions(exercise))
    assert result.passed, result.message
    assert result.total == len(result.checked) > 0
    assert not any(name.startswith("hidden case") for name in result.checked)


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda exercise: exercise.name)
def test_the_solution_edition_passes_the_hidden_cases_of_several_seeds(exercise):
    functions = solution_functions(exercise)
    for seed in SEEDS:
        result = check_function(exercise)(*functions, seed=seed)
        assert result.passed, f"seed {seed}: {result.message}"
        assert result.total >= 3
        assert result.total == len(result.checked)


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda exercise: exercise.name)
def test_hidden_cases_are_named_and_the_same_for_the_same_seed(exercise):
    functions = solution_functions(exercise)
    check = check_function(exercise)
    first, again = (check(*functions, seed=11).message for _ in range(2))
    assert first == again
    assert "hidden case 1:" in first
    assert "hidden case" not in check(*functions).message


def test_another_seed_gives_other_hidden_cases():
    seen = {tuple(check_fan(lambda corners: [(corners[0], corners[k], corners[k + 1])
                                             for k in range(1, len(corners) - 1)], seed=seed).checked)
            for seed in SEEDS}
    assert len(seen) > 1


def fan_fitted_to_the_public_cases(corners):
    """A slip the public cases cannot see: they all number the corners 0, 1, 2, ..., so
    writing the first corner as 0 instead of corners[0] agrees with every one of them."""
    return [(0, corners[k], corners[k + 1]) for k in range(1, len(corners) - 1)]


def test_an_answer_fitted_to_the_public_cases_passes_them_and_fails_a_hidden_one():
    public = check_fan(fan_fitted_to_the_public_cases)
    assert public.passed and public.total == 6
    hidden = check_fan(fan_fitted_to_the_public_cases, seed=3)
    assert not hidden.passed
    assert "hidden case 1: a face of 3 corners with other vertex numbers" in hidden.message
    assert hidden.total == 4 and hidden.checked == []


class ProxyFunction:
    """What the grader's judge hands a check: a callable with a name and a ``__code__``
    holding ``co_consts`` (for ``harness.unfinished``), but no real function behind it
    that a check could inspect or call other than through ``harness.run``."""

    def __init__(self, function):
        self._function = function
        self.__name__ = function.__name__
        self.__qualname__ = function.__qualname__
        self.__code__ = types.SimpleNamespace(co_consts=tuple(function.__code__.co_consts))
        self.calls = 0

    def __call__(self, *arguments):
        self.calls += 1
        return self._function(*arguments)


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda exercise: exercise.name)
def test_a_check_needs_nothing_of_the_learner_function_but_calling_it_and_its_constants(exercise):
    proxies = [ProxyFunction(function) for function in solution_functions(exercise)]
    result = check_function(exercise)(*proxies, seed=5)
    assert result.passed, result.message
    assert all(proxy.calls > 0 for proxy in proxies)


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda exercise: exercise.name)
def test_an_unfinished_function_still_reports_how_many_cases_the_check_runs(exercise):
    def blank(*arguments):
        return ...

    result = check_function(exercise)(*(blank for _ in exercise.functions))
    assert not result.passed and result.checked == []
    assert result.total >= 1
    hidden = check_function(exercise)(*(blank for _ in exercise.functions), seed=3)
    assert hidden.total >= 3
