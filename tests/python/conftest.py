"""Fixtures shared by the Python tests."""
import importlib.util
import os
import pathlib

import pytest

SRC = pathlib.Path(os.environ.get("CAMDYN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="module")
def plot_module():
    """scripts/camdyn_plot.py as a module (skips without matplotlib)."""
    pytest.importorskip("matplotlib")
    spec = importlib.util.spec_from_file_location("camdyn_plot", SRC / "scripts" / "camdyn_plot.py")
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    return m
