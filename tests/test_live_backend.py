"""HALFEDGE_EDU_LIVE_BACKEND: the one setting a hub uses to choose where live views draw."""

from __future__ import annotations

import pytest

from halfedge_edu import live_backend


def test_unset_or_empty_keeps_the_server_rendered_view(monkeypatch):
    monkeypatch.delenv(live_backend.ENV_VARIABLE, raising=False)
    assert live_backend.trame_mode() == "trame"
    monkeypatch.setenv(live_backend.ENV_VARIABLE, " ")
    assert live_backend.trame_mode() == "trame"


@pytest.mark.parametrize(("setting", "mode"), [("server", "trame"), ("client", "client"), (" Client ", "client")])
def test_the_variable_chooses_the_trame_mode(monkeypatch, setting, mode):
    monkeypatch.setenv(live_backend.ENV_VARIABLE, setting)
    assert live_backend.trame_mode() == mode


def test_an_argument_wins_over_the_variable(monkeypatch):
    monkeypatch.setenv(live_backend.ENV_VARIABLE, "client")
    assert live_backend.trame_mode("server") == "trame"


def test_a_wrong_value_names_the_variable_and_the_value(monkeypatch):
    monkeypatch.setenv(live_backend.ENV_VARIABLE, "wasm")
    with pytest.raises(ValueError, match=r"HALFEDGE_EDU_LIVE_BACKEND='wasm'"):
        live_backend.trame_mode()
    with pytest.raises(ValueError, match=r"setting='gpu'"):
        live_backend.trame_mode("gpu")
