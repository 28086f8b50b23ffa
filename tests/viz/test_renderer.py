"""Choosing the renderer: argument, then $HALFEDGE_EDU_VIZ, then automatic."""

from __future__ import annotations

import pytest

from halfedge_edu.viz.renderer import ENV_VARIABLE, choose_mode, show, without_wasm_notice


def test_explicit_mode_wins_over_the_environment(monkeypatch):
    monkeypatch.setenv(ENV_VARIABLE, "live")
    assert choose_mode("static") == "static"


@pytest.mark.parametrize("value", ["static", "live", "STATIC", " live "])
def test_environment_variable_chooses_the_mode(monkeypatch, value):
    monkeypatch.setenv(ENV_VARIABLE, value)
    assert choose_mode() == value.strip().lower()


def test_automatic_mode_outside_a_notebook_is_static(monkeypatch):
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    assert choose_mode() == "static"
    assert choose_mode("auto") == "static"


def test_unknown_mode_is_refused_with_the_choices(monkeypatch):
    monkeypatch.setenv(ENV_VARIABLE, "webgl")
    with pytest.raises(ValueError, match="HALFEDGE_EDU_VIZ='webgl'.*static"):
        choose_mode()


def test_the_wasm_notice_is_left_out_and_everything_else_printed_goes_through(capsys):
    with without_wasm_notice():
        print("before")
        print("Using wasm_dir: /somewhere/vtk-wasm-empty")
        print("Using wasm_dir: /somewhere/vtk-wasm-empty")
        print("after", "it")
    assert capsys.readouterr().out == "before\nafter it\n"


def test_show_outside_a_live_lab_is_plotter_show():
    shown = []

    class Plotter:
        def show(self, **kwargs):
            shown.append(kwargs)

    show(Plotter())
    assert shown == [{}]
