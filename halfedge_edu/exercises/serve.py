"""The learner's side of a graded run: answer the judge's calls from inside the notebook's kernel.

The grader appends one cell to the learner's notebook; it calls :func:`serve`, which
connects to the judge's socket and, for each request, calls the learner's function
with the arguments the judge sent and sends back what it answered (see
:mod:`halfedge_edu.exercises.wire`). Nothing here decides a score: the judge checks
every answer itself, so whatever the learner's cells did to this module changes at
most what *their* functions answer.

"Write it yourself", kept here: while the learner's function runs, each package
function that holds the exercise's answer (``Exercise.forbids`` in
:mod:`~halfedge_edu.exercises.grading`: ``HalfedgeMesh.flip``, ``Vertex.neighbors``,
the chapter's own ``rings_only`` ...) refuses a call that comes from the learner's
code and reports "this is the exercise" instead; the same functions called by other
package code (``mesh.validate()`` inside the learner's function, say) work as usual.
A learner's function that *is* a package function (``from ... import _de_casteljau as
my_de_casteljau``) is refused the same way. The refusal swaps the function's code
object, so every alias and bound method of it is covered.
"""

from __future__ import annotations

import functools
import importlib
import inspect
import socket
import sysconfig
import traceback
import types
from pathlib import Path

from . import wire
from .harness import _time_limit, _TookTooLong

#: Prefix of a ``forbids`` entry that names a function the chapter's own cells define.
NOTEBOOK = "notebook:"


class ThisIsTheExercise(BaseException):
    """Raised in the learner's function when it calls the package's own answer.

    A BaseException, so that ``except Exception`` in the learner's code does not hide it.
    """


_LIBRARY_FOLDERS = tuple(
    str(Path(p).resolve()) for p in {sysconfig.get_paths()[k] for k in ("stdlib", "platstdlib", "purelib", "platlib")}
) + (str(Path(__file__).resolve().parents[1]),)


@functools.lru_cache(maxsize=4096)
def is_library_file(filename: str) -> bool:
    """Whether code in ``filename`` is library code (the package, the standard library, site-packages).

    Cached: every call of a guarded function asks it about its caller's file.
    """
    if not filename or filename.startswith("<frozen"):
        return True
    try:
        resolved = str(Path(filename).resolve())
    except (OSError, ValueError):
        return False
    return resolved.startswith(_LIBRARY_FOLDERS)


class _Guards:
    """The package's answers, made to refuse calls from the learner's code while a graded call runs."""

    def __init__(self):
        self.originals: dict[str, types.FunctionType] = {}   # key -> a copy that runs the real code
        self.active: set[str] = set()                        # keys refused during the current call
        self.in_call = False
        self.used: list[str] = []                            # what the learner's code called
        self.keys: dict[int, str] = {}                       # id(guarded function) -> its key
        self.guarded: list[types.FunctionType] = []

    def install(self, key: str, function: types.FunctionType) -> str | None:
        """Give ``function`` the guard's code; keep a callable copy with its original code.

        Returns the key the guard answers to: ``key``, or the key ``function`` was guarded
        under before (one function can be named by two entries: a method and its module);
        None for what cannot be guarded (a closure cannot take another code object).
        """
        if not isinstance(function, types.FunctionType):
            return None
        if id(function) in self.keys:
            return self.keys[id(function)]
        if key in self.originals or function.__code__.co_freevars:
            return None
        copy = types.FunctionType(function.__code__, function.__globals__, function.__name__,
                                  function.__defaults__, function.__closure__)
        copy.__kwdefaults__ = function.__kwdefaults__
        self.originals[key] = copy
        self.keys[id(function)] = key
        self.guarded.append(function)                        # keeps id(function) unique
        try:  # introspection (``inspect.signature``, ``help``) still sees the real parameters
            function.__signature__ = inspect.signature(copy)
        except (TypeError, ValueError):
            pass
        function.__code__ = _guard_code(key)
        return key

    def call(self, key: str, caller: types.FrameType | None, args: tuple, kwargs: dict):
        original = self.originals[key]
        from_learner = caller is not None and not is_library_file(caller.f_code.co_filename)
        if self.in_call and key in self.active and from_learner:
            self.used.append(key)
            raise ThisIsTheExercise(f"{_short(key)} is the package's own answer to this exercise; "
                                    f"write it yourself from the pointers")
        return original(*args, **kwargs)


_GUARDS = _Guards()


def uninstall_guards() -> None:
    """Give every guarded function its own code back (for tests that judge in one process;
    a graded kernel ends with its run)."""
    for function in _GUARDS.guarded:
        key = _GUARDS.keys[id(function)]
        function.__code__ = _GUARDS.originals[key].__code__
        function.__dict__.pop("__signature__", None)
    _GUARDS.__init__()


def _guard_code(key: str) -> types.CodeType:
    namespace: dict = {}
    exec(  # noqa: S102 - fixed source; only the key varies, and it is passed as data
        "def guard(*args, **kwargs):\n"
        "    import sys\n"
        "    from halfedge_edu.exercises.serve import _GUARDS\n"
        f"    return _GUARDS.call({key!r}, sys._getframe(1), args, kwargs)\n",
        namespace,
    )
    return namespace["guard"].__code__


def _short(key: str) -> str:
    if key.startswith(NOTEBOOK):
        return f"the chapter's {key[len(NOTEBOOK):]}"
    parts = key.split(".")
    return ".".join(parts[-2:]) if parts[-2][:1].isupper() else parts[-1]


def resolve(key: str, namespace: dict):
    """The function a ``forbids`` entry names: ``"notebook:NAME"`` in the notebook,
    else a dotted path (a module, then attributes; a property's getter)."""
    if key.startswith(NOTEBOOK):
        return namespace.get(key[len(NOTEBOOK):])
    parts = key.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            found = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        for attribute in parts[cut:]:
            found = vars(found).get(attribute) if isinstance(found, type) else getattr(found, attribute, None)
            if isinstance(found, (property, staticmethod, classmethod)):
                found = found.fget if isinstance(found, property) else found.__func__
        return found
    return None


#: Prefix of a ``forbids`` entry that names a function the learner may call although its
#: module is forbidden (``"!halfedge_edu.algorithms.simplify.face_quadrics"``).
ALLOWED = "!"


def functions_forbidden(keys: list[str], namespace: dict) -> dict[str, types.FunctionType]:
    """Every function the ``forbids`` entries ``keys`` name, by key: a function or method
    as itself; a whole module as each function it defines and each method of each class
    it defines, a package as all of its modules' (``algorithms.remesh`` is its five
    phase files) (so that a learner's wrapper, ``lambda m: loop_subdivide(m)``, is refused as
    the alias ``my_upsample = loop_subdivide`` is); less the entries marked allowed."""
    allowed = {key[len(ALLOWED):] for key in keys if key.startswith(ALLOWED)}
    found: dict[str, types.FunctionType] = {}
    for key in keys:
        if key.startswith(ALLOWED):
            continue
        target = resolve(key, namespace)
        if isinstance(target, types.ModuleType):
            for module in _modules_of(target):
                found.update(_functions_of_module(module))
        elif isinstance(target, types.FunctionType):
            found[key] = target
    return {key: function for key, function in found.items() if key not in allowed}


def install_guards(forbids: dict[str, list[str]], namespace: dict) -> dict[str, list[str]]:
    """Guard every function each exercise's ``forbids`` entries name; per exercise, the
    keys its graded calls refuse (what :func:`_answer` takes)."""
    expanded: dict[str, list[str]] = {}
    for exercise, keys in forbids.items():
        functions = functions_forbidden(keys, namespace)
        installed = (_GUARDS.install(key, function) for key, function in functions.items())
        expanded[exercise] = [key for key in installed if key is not None]
    return expanded


def _modules_of(module: types.ModuleType) -> list[types.ModuleType]:
    """``module``, and when it is a package every module below it (imported here: a
    package's ``__init__`` defines little itself, its functions live in its files)."""
    import importlib
    import pkgutil

    found = [module]
    for info in pkgutil.walk_packages(getattr(module, "__path__", ()), prefix=f"{module.__name__}."):
        found.append(importlib.import_module(info.name))
    return found


def _functions_of_module(module: types.ModuleType) -> dict[str, types.FunctionType]:
    """``module``'s own functions and its classes' methods (getters of properties, static
    and class methods included), keyed by ``module.qualname``."""
    name = module.__name__
    found: dict[str, types.FunctionType] = {}
    for attribute, value in vars(module).items():
        if isinstance(value, types.FunctionType) and value.__module__ == name:
            found[f"{name}.{attribute}"] = value
        elif isinstance(value, type) and value.__module__ == name:
            for member_name, member in vars(value).items():
                if isinstance(member, property):
                    member = member.fget
                elif isinstance(member, (staticmethod, classmethod)):
                    member = member.__func__
                if isinstance(member, types.FunctionType):
                    found[f"{name}.{value.__qualname__}.{member_name}"] = member
    # Only code written in the module: not what namedtuple or dataclass generated (their
    # __new__, __init__, __repr__ ... run with globals of their own, and are no answer).
    return {key: function for key, function in found.items() if function.__globals__ is vars(module)}


def _package_origin(function) -> str | None:
    """The package function ``function`` is (or wraps), else None."""
    target = getattr(function, "func", function)  # functools.partial
    target = getattr(target, "__func__", target)  # bound method
    code = getattr(target, "__code__", None)
    if code is None:
        return None
    if code.co_name == "guard" and code.co_filename == "<string>":
        return "a function of the package"
    if is_library_file(code.co_filename):
        return f"{getattr(target, '__module__', '?')}.{getattr(target, '__qualname__', '?')}"
    return None


# --------------------------------------------------------------------------------------
# The serving loop
# --------------------------------------------------------------------------------------

def describe(namespace: dict, names: list[str]) -> dict:
    """What the judge needs to know of each function before calling it."""
    found = {}
    for name in names:
        function = namespace.get(name)
        code = getattr(function, "__code__", None)
        found[name] = {
            "callable": callable(function),
            "blanks": bool(code is not None and any(c is Ellipsis for c in code.co_consts)),
            "package": _package_origin(function) if callable(function) else None,
        }
    return found


def serve(namespace: dict, address: str, forbids: dict[str, list[str]]) -> None:
    """Answer the judge's calls until it says it is done or closes the connection.

    Args:
        namespace: the notebook's globals (where the learner's functions are).
        address: the judge's Unix socket.
        forbids: per exercise, the ``forbids`` entries to refuse while its function runs.
    """
    forbids = install_guards(forbids, namespace)
    connection = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    connection.connect(address)
    try:
        while True:
            try:
                request = wire.receive(connection)
            except EOFError:
                return
            kind = request.get("do")
            if kind == "done":
                return
            if kind == "describe":
                wire.send(connection, {"id": request.get("id"), "functions": describe(namespace, request["names"])})
            elif kind == "call":
                wire.send(connection, _answer(namespace, request, forbids))
    finally:
        connection.close()


def _answer(namespace: dict, request: dict, forbids: dict[str, list[str]]) -> dict:
    """Call the learner's function as the request says; the reply, whatever happened."""
    reply: dict = {"id": request.get("id")}
    name = request["function"]
    function = namespace.get(name)
    from halfedge_edu.core.mesh import HalfedgeMesh

    meshes: list = []

    def new_mesh(state: dict):
        mesh = object.__new__(HalfedgeMesh)
        for key, value in state.items():
            setattr(mesh, key, wire.array_of(value) if isinstance(value, dict) else value)
        mesh._cache = {}
        meshes.append(mesh)
        return mesh

    try:
        args = []
        for data in request["args"]:
            if isinstance(data, dict) and data.get("t") == "mesh" and data.get("state") is not None:
                args.append(new_mesh(data["state"]))
            else:
                args.append(wire.decode(data, meshes))
    except Exception as error:  # the judge's own message: report, do not crash the kernel
        reply["error"] = {"type": "WireError", "message": str(error)[:500], "traceback": ""}
        return reply

    origin = _package_origin(function)
    _GUARDS.active = set(forbids.get(request.get("exercise", ""), []))
    _GUARDS.used = []
    _GUARDS.in_call = True
    try:
        if origin is not None:
            raise ThisIsTheExercise(f"{name} is {origin}, the package's own function; write it yourself")
        with _time_limit(float(request.get("seconds", 0)) or 3600.0):
            value = function(*args)
        reply["value"] = wire.encode(value, meshes)
    except _TookTooLong:
        reply["timeout"] = True
    except ThisIsTheExercise as error:
        reply["forbidden"] = str(error)[:500]
    except BaseException as error:  # the learner's bug (or SystemExit, KeyboardInterrupt): report it
        reply["error"] = {"type": type(error).__name__[:80], "message": _text(error)[:2000],
                          "traceback": _learner_traceback(error)[:4000]}
    finally:
        _GUARDS.in_call = False
        _GUARDS.active = set()
    if _GUARDS.used and "forbidden" not in reply:
        reply["forbidden"] = (f"{_short(_GUARDS.used[0])} is the package's own answer to this exercise; "
                              f"write it yourself from the pointers")
    try:
        reply["args"] = [wire.encode(arg, meshes) if not isinstance(arg, HalfedgeMesh)
                         else {"t": "mesh", "arg": -1, "state": wire.mesh_state(arg)} for arg in args]
    except Exception as error:  # an argument the learner turned into something that does not cross
        reply.pop("value", None)
        reply["error"] = {"type": "WireError", "message": f"an argument cannot be sent back: {error}"[:500],
                          "traceback": ""}
    return reply


def _text(error: BaseException) -> str:
    try:
        return str(error)
    except Exception:
        return "<the exception's message could not be printed>"


def _learner_traceback(error: BaseException) -> str:
    """The traceback lines of the learner's own code (not this module's frame)."""
    frames = [frame for frame in traceback.extract_tb(error.__traceback__)
              if not frame.filename.endswith("exercises/serve.py")]
    lines = traceback.format_list(frames) + traceback.format_exception_only(type(error), error)
    return "".join(lines)
