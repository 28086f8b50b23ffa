"""Importing the viz package is light: pyvista and ipywidgets wait for the first scene."""

from __future__ import annotations

import subprocess
import sys


def test_importing_viz_loads_no_plotting_library():
    code = ("import sys, halfedge_edu.viz; "
            "print(sorted(m for m in ('pyvista', 'vtk', 'vtkmodules', 'ipywidgets') if m in sys.modules))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "[]"


def test_importing_the_package_does_not_import_viz():
    code = "import sys, halfedge_edu; print('halfedge_edu.viz' in sys.modules)"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "False"
