"""Shared fixtures of the Python tests: where the models and the pcr tool are (set by CTest,
tests/python.cmake), and a runner of the tool whose JSON (17 significant digits, exact for a double)
is the C++ reference the bindings must reproduce bit for bit."""
import json
import os
import subprocess

import pytest

MODEL_DIR = os.environ.get("PCR_MODEL_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "models"))
PCR_TOOL = os.environ.get("PCR_TOOL", "pcr")


def model_path(name):
    return os.path.join(MODEL_DIR, name + ".urdf")


def run_tool(*args):
    """Runs the pcr tool with --json; returns the parsed JSON (the command must exit 0)."""
    done = subprocess.run([PCR_TOOL, *args, "--json"], capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


@pytest.fixture(scope="session")
def stewart():
    import pcr
    return pcr.load_model(model_path("stewart_gough"))


@pytest.fixture(scope="session")
def planar():
    import pcr
    return pcr.load_model(model_path("planar_three_rod"))
