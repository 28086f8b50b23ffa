"""The solution edition's own exercise functions, taken from ``notebooks/src`` for tests.

    read_obj, write_obj = solution_functions(exercise)    # an ``Exercise`` of ``grading.EXERCISES``

Each chapter source is parsed, its imports and top-level functions are run in a fresh
namespace (``np`` and ``hx`` given), and the functions the exercise names are returned,
so a test judges exactly what the chapter's solution edition defines.
"""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Callable

import numpy as np

import halfedge_edu as hx
from halfedge_edu.exercises.grading import Exercise

SOURCES = Path(__file__).resolve().parents[2] / "notebooks" / "src"


def chapter_namespace(chapter: str) -> dict:
    """Imports and functions of chapter ``chapter``'s source (other top-level code is not run)."""
    (path,) = SOURCES.glob(f"{chapter}_*.py")
    namespace: dict = {"np": np, "hx": hx}
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, (ast.Import, ast.ImportFrom, ast.FunctionDef)):
            try:
                exec(compile(ast.Module([node], []), str(path), "exec"), namespace)
            except NameError:      # a default value naming a notebook global: not an exercise function
                pass
    return namespace


def solution_functions(exercise: Exercise) -> list[Callable]:
    """The functions ``exercise`` grades, as the chapter's solution edition defines them."""
    namespace = chapter_namespace(exercise.chapter)
    return [namespace[name] for name in exercise.functions]
