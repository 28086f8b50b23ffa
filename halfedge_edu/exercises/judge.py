"""The judge: run the package's checks on a learner's functions that live in another process.

    python -m halfedge_edu.exercises.judge --handoff-fd 3 --exercises flip --seed 1234

The grader starts this process for each submission, next to the sandbox in which the
learner's notebook runs. The judge imports the checks itself, before any learner code
exists anywhere near it, and never runs learner code: each learner function is a
:class:`RemoteFunction`, a proxy that sends its arguments to the notebook's kernel
(:mod:`halfedge_edu.exercises.serve`) and turns the answer back into Python values
(:mod:`halfedge_edu.exercises.wire`). So nothing the learner's cells do (patching
``numpy.allclose`` or a check, a hook that prints a fake line, a module planted in
``sys.modules``) reaches the code that decides the score.

Each exercise runs twice: the public cases (what the chapter's check cell shows) and
hidden cases drawn from ``--seed`` (the check's ``seed=`` argument), as otter-grader's
hidden tests do. It earns its points only when both pass and the learner's function
never called the package's own answer.

It prints one line of JSON, ``{"exercises": {NAME: {...}}}``, which the grader validates.
"""

from __future__ import annotations

import argparse
import builtins
import inspect
import json
import socket
import sys
import types

import numpy as np

from halfedge_edu.core.mesh import HalfedgeMesh

from . import harness, wire

#: Seconds the judge waits for the kernel's answer beyond the check's own limit before it
#: takes the kernel for gone (a learner's code that blocks signals).
GRACE = 10.0


class KernelGone(Exception):
    """The notebook's kernel stopped answering."""


class UsedTheAnswer(Exception):
    """The learner's function called the package's own answer (reported by the kernel)."""


class Link:
    """The judge's end of the socket: numbered requests, replies matched by number."""

    def __init__(self, connection: socket.socket):
        self.connection = connection
        self.last_id = 0
        self.gone: str | None = None
        self.forbidden: dict[str, str] = {}      # exercise -> the first "this is the exercise" message

    def ask(self, request: dict, seconds: float) -> dict:
        if self.gone:
            raise KernelGone(self.gone)
        self.last_id += 1
        request["id"] = self.last_id
        self.connection.settimeout(seconds + GRACE)
        try:
            wire.send(self.connection, request)
            while True:
                reply = wire.receive(self.connection)
                if reply.get("id") == self.last_id:
                    return reply
        except (OSError, EOFError, wire.WireError) as error:
            self.gone = f"the notebook's kernel stopped answering ({type(error).__name__}: {error})"
            raise KernelGone(self.gone) from None

    def describe(self, names: list[str]) -> dict:
        functions = self.ask({"do": "describe", "names": names}, 30.0).get("functions")
        if not isinstance(functions, dict):
            raise KernelGone("the notebook's kernel answered the judge's first question with nonsense")
        return functions

    def call(self, exercise: str, name: str, args: tuple):
        meshes: list = []
        encoded = []
        for arg in args:
            if isinstance(arg, HalfedgeMesh):
                meshes.append(arg)
                encoded.append({"t": "mesh", "arg": -1, "state": wire.mesh_state(arg)})
            else:
                encoded.append(wire.encode(arg, meshes))
        seconds = harness.limit_now()
        reply = self.ask({"do": "call", "exercise": exercise, "function": name, "args": encoded,
                          "seconds": seconds}, seconds)
        if "forbidden" in reply:
            self.forbidden.setdefault(exercise, str(reply["forbidden"])[:500])
            raise UsedTheAnswer(str(reply["forbidden"])[:500])
        if reply.get("timeout"):
            raise harness._TookTooLong
        _put_back(args, reply.get("args"))
        if "error" in reply:
            raise _learner_error(reply["error"])
        if "value" not in reply:
            raise wire.WireError("the kernel's reply holds no value")
        return wire.decode(reply["value"], meshes, _new_mesh)


def _put_back(args: tuple, returned) -> None:
    """Make the judge's arguments what the learner's function left them (it may work in place)."""
    if not isinstance(returned, list) or len(returned) != len(args):
        raise wire.WireError("the kernel sent back another number of arguments")
    for arg, data in zip(args, returned):
        if isinstance(arg, HalfedgeMesh):
            if not isinstance(data, dict) or not isinstance(data.get("state"), dict):
                raise wire.WireError("the mesh did not come back")
            wire.apply_mesh_state(arg, data["state"])
        elif isinstance(arg, np.ndarray) and arg.flags.writeable:
            new = wire.decode(data)
            if isinstance(new, np.ndarray) and new.shape == arg.shape:
                np.copyto(arg, new, casting="unsafe")
        elif isinstance(arg, list):
            new = wire.decode(data)
            if isinstance(new, list):
                arg[:] = new
        elif isinstance(arg, dict):
            new = wire.decode(data)
            if isinstance(new, dict):
                arg.clear()
                arg.update(new)


def _new_mesh(state: dict) -> HalfedgeMesh:
    """A mesh the learner's function made and returned (not one of its arguments)."""
    mesh = HalfedgeMesh.from_faces(np.eye(3), [[0, 1, 2]])
    wire.apply_mesh_state(mesh, state)
    return mesh


_GENERATED: dict[str, type] = {}


def _learner_error(data) -> Exception:
    """The learner's exception, rebuilt here: the builtin type of that name (so the checks'
    ``isinstance(error, NotImplementedError)`` still works), else an Exception subclass with
    the learner's class name; ``learner_traceback`` holds their traceback text."""
    if not isinstance(data, dict):
        data = {}
    name = str(data.get("type", "Exception"))[:80]
    message = str(data.get("message", ""))[:2000]
    kind = getattr(builtins, name, None)
    if not (isinstance(kind, type) and issubclass(kind, Exception)):
        if not name.isidentifier():
            name = "LearnerError"
        kind = _GENERATED.setdefault(name, type(name, (Exception,), {"__module__": "learner"}))
    try:
        error = kind(message)
    except Exception:  # a builtin whose constructor wants other arguments (UnicodeDecodeError, say)
        kind = _GENERATED.setdefault(name + "_", type(name, (Exception,), {"__module__": "learner"}))
        error = kind(message)
    error.learner_traceback = str(data.get("traceback", ""))[:4000]
    return error


class RemoteFunction:
    """A learner's function as the checks see it: calling it asks the kernel to call the real one."""

    def __init__(self, link: Link, exercise: str, name: str, info: dict):
        self._link, self._exercise = link, exercise
        self.__name__ = self.__qualname__ = name
        # harness.unfinished looks for a ``...`` among the constants of the function's code.
        self.__code__ = types.SimpleNamespace(co_consts=(Ellipsis,) if info.get("blanks") else ())

    def __call__(self, *args):
        return self._link.call(self._exercise, self.__name__, args)


def _cases(result) -> list[int]:
    """[agreed, total] from a CheckResult (total from ``result.total`` where the check says it)."""
    checked = len(getattr(result, "checked", []) or [])
    total = getattr(result, "total", None)
    if not isinstance(total, int):
        total = checked if result else checked + 1
    return [checked, max(total, checked)]


def judge(link: Link, exercises: list, seed: int) -> dict:
    """Run each exercise's checks on the learner's functions behind ``link``; plain data per exercise."""
    from .grading import check_function

    wanted = sorted({name for exercise in exercises for name in exercise.functions})
    functions = link.describe(wanted)
    results = {}
    for exercise in exercises:
        infos = [functions.get(name) if isinstance(functions.get(name), dict) else {} for name in exercise.functions]
        missing = [name for name, info in zip(exercise.functions, infos) if info.get("callable") is not True]
        package = [(name, info["package"]) for name, info in zip(exercise.functions, infos)
                   if isinstance(info.get("package"), str)]
        entry = {"passed": False, "output": "", "public": [0, 0], "hidden": [0, 0], "missing": missing,
                 "forbidden": None}
        results[exercise.name] = entry
        if missing:
            entry["output"] = (f"no function named {', '.join(missing)} was defined: the exercise cell defines "
                               f"{' and '.join(exercise.functions)}; keep those names")
            continue
        if package:
            name, origin = package[0]
            entry["forbidden"] = entry["output"] = (f"{name} is {origin}, the package's own function. This is the "
                                                    f"exercise: write it yourself from the pointers.")
            continue
        proxies = [RemoteFunction(link, exercise.name, name, info) for name, info in zip(exercise.functions, infos)]
        check = check_function(exercise)
        try:
            public = check(*proxies)
            entry["public"] = _cases(public)
            entry["output"] = str(public.message)
            passed = bool(public)
            if passed and "seed" in inspect.signature(check).parameters:
                hidden = check(*proxies, seed=seed)
                entry["hidden"] = _cases(hidden)
                if not hidden:
                    passed = False
                    entry["output"] = f"The public cases pass, but a hidden case does not. {hidden.message}"
        except KernelGone as gone:
            passed = False
            entry["output"] = str(gone)
        except Exception as error:  # a check that broke on what the kernel sent: the exercise fails
            passed = False
            entry["output"] = f"the check could not finish: {type(error).__name__}: {error}"[:2000]
        if exercise.name in link.forbidden:
            passed = False
            entry["forbidden"] = entry["output"] = f"This is the exercise: {link.forbidden[exercise.name]}."
        entry["passed"] = passed
        entry["output"] = entry["output"][:4000]
    return results


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m halfedge_edu.exercises.judge")
    parser.add_argument("--handoff-fd", type=int, required=True,
                        help="a Unix socket on which the grader passes the kernel's connection")
    parser.add_argument("--exercises", required=True, help="comma-separated exercise names")
    parser.add_argument("--seed", type=int, required=True, help="the seed of the hidden cases")
    args = parser.parse_args(argv)

    from .grading import EXERCISES

    by_name = {exercise.name: exercise for exercise in EXERCISES}
    exercises = [by_name[name] for name in args.exercises.split(",")]
    handoff = socket.socket(fileno=args.handoff_fd)
    try:
        _, fds, _, _ = socket.recv_fds(handoff, 1, 1)
    except OSError:
        fds = []
    handoff.close()
    if not fds:  # the run ended without reaching the grading cell
        print(json.dumps({"connected": False}), flush=True)
        return 0
    connection = socket.socket(fileno=fds[0])
    link = Link(connection)
    try:
        results = judge(link, exercises, args.seed)
    except KernelGone as gone:
        print(json.dumps({"connected": True, "problem": str(gone)[:1000]}), flush=True)
        return 0
    try:
        link.connection.settimeout(5)
        wire.send(link.connection, {"do": "done"})
    except OSError:
        pass
    print(json.dumps({"connected": True, "exercises": results}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
