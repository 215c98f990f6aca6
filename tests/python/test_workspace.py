"""The workspace sampler from Python: the same samples as the pcr tool bit for bit, independent of the
threads, and spread over a Dask LocalCluster by examples/python/workspace_dask.py with the same points."""
import os
import subprocess
import sys

import numpy as np

import pcr
from conftest import MODEL_DIR, model_path, run_tool

EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "python")


def positions(result):
    return {s.index: s.platforms[0].position.tolist() for s in result.samples if s.converged}


def test_samples_equal_the_tool_and_do_not_depend_on_threads(planar):
    one = pcr.sample_workspace(planar, samples=6, seed=3, threads=1)
    two = pcr.sample_workspace(planar, samples=6, seed=3, threads=2)
    assert [s.index for s in one.samples] == list(range(6))
    assert positions(one) == positions(two)
    assert len(positions(one)) == 6 - one.failures
    ref = run_tool("workspace", model_path("planar_three_rod"), "--samples", "6", "--seed", "3")
    assert ref["failures"] == one.failures
    for point in ref["points"]:
        sample = one.samples[point["index"]]
        assert sample.inputs.tolist() == point["inputs"]
        if point["status"] == "converged":
            assert sample.platforms[0].position.tolist() == point["platforms"]["platform"]["position"]


def test_samples_carry_the_tools_verdicts(planar):
    got = pcr.sample_workspace(planar, samples=2, seed=3, stability_verdict=True)
    ref = run_tool("workspace", model_path("planar_three_rod"), "--samples", "2", "--seed", "3",
                   "--stability")
    for point in ref["points"]:
        sample = got.samples[point["index"]]
        if point["status"] == "converged":
            assert sample.stability.verdict == point["stability"]["verdict"]
            assert sample.stability.margin == point["stability"]["margin"]
        else:
            assert sample.stability.verdict == "not_checked"
    assert pcr.sample_workspace(planar, samples=1, seed=3).samples[0].stability.verdict == "not_checked"


def test_split_runs_give_the_same_samples(planar):
    whole = pcr.sample_workspace(planar, samples=4, seed=5)
    tail = pcr.sample_workspace(planar, samples=2, seed=5, first_sample=2)
    assert [s.index for s in tail.samples] == [2, 3]
    for s in tail.samples:
        assert s.inputs.tolist() == whole.samples[s.index].inputs.tolist()
        assert s.platforms[0].position.tolist() == whole.samples[s.index].platforms[0].position.tolist()


def test_dask_example_gives_the_threaded_points(tmp_path):
    # The example spreads 8 samples of seed 7 over a LocalCluster in chunks of 3 and writes the
    # platform positions; they must equal one threaded run's.
    out = tmp_path / "dask_points.npy"
    done = subprocess.run([sys.executable, os.path.join(EXAMPLES, "workspace_dask.py"),
                           model_path("planar_three_rod"), "--samples", "8", "--seed", "7", "--chunk", "3",
                           "--workers", "2", "--out", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    points = np.load(out)
    planar = pcr.load_model(model_path("planar_three_rod"))
    threaded = pcr.sample_workspace(planar, samples=8, seed=7, threads=2)
    expected = np.array([s.platforms[0].position if s.converged else [np.nan] * 3 for s in threaded.samples])
    assert points.shape == (8, 3)
    assert np.array_equal(points, expected, equal_nan=True)


def test_plot_example_writes_a_picture(tmp_path):
    png = tmp_path / "fk.png"
    done = subprocess.run([sys.executable, os.path.join(EXAMPLES, "fk_plot.py"),
                           os.path.join(MODEL_DIR, "stewart_gough.urdf"), str(png)],
                          capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert done.returncode == 0, done.stderr
    assert png.stat().st_size > 10000  # a drawn figure, not an empty canvas
    with open(png, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"
