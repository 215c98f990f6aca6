"""The Python blocks of docs/python.md run as written: in page order, in one namespace (later blocks use
the names of earlier ones: model, fk, ik), from the directory that holds models/ (the page's paths are
relative to the repository root). Each block must run without an exception and the results it makes
must have converged (their values are checked against the pcr tool in the other tests)."""
import os
import re

from conftest import MODEL_DIR

DOC = os.path.join(os.path.dirname(__file__), "..", "..", "docs", "python.md")


def test_python_md_blocks_run_as_written(monkeypatch):
    with open(DOC, encoding="utf-8") as f:
        blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
    assert len(blocks) == 4  # models, forward kinematics, inverse kinematics, the workspace
    monkeypatch.chdir(os.path.dirname(os.path.abspath(MODEL_DIR)))
    names = {}
    results = []
    for k, block in enumerate(blocks, 1):
        exec(compile(block, f"docs/python.md block {k}", "exec"), names)
        results.append(names.get("result"))
    fk_result, ik_result, workspace = results[1], results[2], results[3]
    assert fk_result.converged, fk_result.summary.message
    assert names["rod"].centerline.shape[1] == 3
    assert ik_result.converged, ik_result.summary.message
    assert len(workspace.samples) == 100
    assert all(s.converged for s in workspace.samples)
