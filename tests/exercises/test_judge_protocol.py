"""The judge and the serving loop joined in one process: every graded exercise's solution crosses the wire.

``halfedge-edu grade`` runs the judge and the learner's kernel in two processes joined by
a socket. Here the same two halves run in one process, each request and reply going
through JSON exactly as on the socket, so a few seconds show that every exercise's
arguments and answers (meshes, handles, soups, arrays, paths, None) cross the wire and
that each chapter's solution earns its point this way, public and hidden cases; and that
the package's own answer is refused. The real processes and sandbox: test_grading*.py.
"""

from __future__ import annotations

import json

import pytest

from halfedge_edu.core import ops
from halfedge_edu.exercises import judge, serve
from halfedge_edu.exercises.grading import ANSWER_KEYS, EXERCISES

from .chapter_solutions import chapter_namespace


@pytest.fixture(autouse=True)
def _guards_removed_afterwards():
    """The guards this module installs in the test process go when each test ends, so
    that later tests on this worker run the package's functions unguarded."""
    yield
    serve.uninstall_guards()


class InProcessLink(judge.Link):
    """The judge's link, with the notebook's serving loop answering in this process."""

    def __init__(self, namespace: dict, forbids: dict):
        self.namespace, self.forbids = namespace, forbids
        self.last_id, self.gone, self.forbidden = 0, None, {}

    def ask(self, request: dict, seconds: float) -> dict:
        self.last_id += 1
        request = json.loads(json.dumps(dict(request, id=self.last_id), allow_nan=False))
        if request["do"] == "describe":
            reply = {"id": self.last_id, "functions": serve.describe(self.namespace, request["names"])}
        else:
            reply = serve._answer(self.namespace, request, self.forbids)
        return json.loads(json.dumps(reply, allow_nan=False))


def _judged(namespace: dict, exercises: list) -> dict:
    forbids = serve.install_guards({e.name: [*e.forbids, *ANSWER_KEYS] for e in exercises}, namespace)
    return judge.judge(InProcessLink(namespace, forbids), exercises, seed=20261128)


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda e: e.name)
def test_each_chapters_solution_earns_its_point_across_the_wire_public_and_hidden(exercise):
    result = _judged(chapter_namespace(exercise.chapter), [exercise])[exercise.name]
    assert result["passed"] is True, result["output"]
    assert result["public"][0] == result["public"][1] > 0, result
    assert result["hidden"][0] == result["hidden"][1] > 0, result


def test_the_packages_own_flip_is_refused_across_the_wire():
    flip = next(e for e in EXERCISES if e.name == "flip")
    result = _judged({"my_flip": lambda mesh, e: mesh.flip(e)}, [flip])["flip"]
    assert result["passed"] is False and "This is the exercise" in result["output"], result


def test_the_packages_own_split_is_refused_across_the_wire():
    split = next(e for e in EXERCISES if e.name == "split")
    for learner in (lambda mesh, e: mesh.split(e), lambda mesh, e: ops.split(mesh, e)):
        result = _judged({"my_split": learner}, [split])["split"]
        assert result["passed"] is False and "This is the exercise" in result["output"], result


def _forbidden_modules() -> list[tuple[str, str, str]]:
    """(exercise, forbidden module, one function it defines) for every module an exercise
    forbids, the checks' own modules (ANSWER_KEYS) included."""
    import importlib
    import types

    cases = []
    for exercise in EXERCISES:
        for key in (*exercise.forbids, *ANSWER_KEYS):
            try:
                module = importlib.import_module(key)
            except ImportError:
                continue                                   # a function or method, not a module
            exempt = {entry[1:] for entry in exercise.forbids if entry.startswith("!")}
            functions = sorted(name for name, value in vars(module).items()
                               if isinstance(value, types.FunctionType) and value.__module__ == key
                               and not value.__code__.co_freevars and f"{key}.{name}" not in exempt)
            cases.append((exercise.name, key, functions[0]))
    return cases


@pytest.mark.parametrize(("name", "module", "function"), _forbidden_modules(),
                         ids=lambda value: value.rsplit(".", 1)[-1])
def test_a_learners_wrapper_around_any_function_of_a_forbidden_module_is_refused(name, module, function):
    """``my_upsample = lambda m: loop_subdivide(m)`` is the package's answer as much as
    ``my_upsample = loop_subdivide``: a whole module in ``forbids`` guards each function it defines."""
    import importlib

    exercise = next(e for e in EXERCISES if e.name == name)
    answer = getattr(importlib.import_module(module), function)
    wrapper = lambda *args, **kwargs: answer(*args, **kwargs)  # noqa: E731 - as a learner writes it
    result = _judged({learner_name: wrapper for learner_name in exercise.functions}, [exercise])[name]
    assert result["passed"] is False and "This is the exercise" in result["output"], (module, function, result)


@pytest.mark.parametrize(("name", "reference"), [("collapse_short_edges", "collapse_short_edges_reference"),
                                               ("tangential_smoothing", "tangential_smoothing_reference")])
def test_the_checks_own_answer_is_refused_across_the_wire_even_wrapped(name, reference):
    """A whole module in ``forbids`` only refuses a learner's function that *is* one of its
    functions; the checks' reference answers are named one by one, so a call to them is refused too."""
    from halfedge_edu.exercises import remesh_checks

    exercise = next(e for e in EXERCISES if e.name == name)
    answer = getattr(remesh_checks, reference)
    for learner in (answer, lambda *args: answer(*args)):
        result = _judged({exercise.functions[0]: learner}, [exercise])[name]
        assert result["passed"] is False and "This is the exercise" in result["output"], result
