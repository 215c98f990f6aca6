"""Loading models from Python: names, defaults and bounds as in the file, bad input as pcr.InputError
with the C++ message."""
import numpy as np
import pytest

import pcr
from conftest import model_path


def test_model_tables(stewart):
    # The numbers of models/stewart_gough.urdf: six fed legs leg0..leg5 of 0.45 m in [0.2, 0.8] m,
    # one platform, gravity (0, 0, -9.81) m/s^2.
    assert stewart.name == "stewart_gough"
    assert stewart.input_names == ["leg%d" % i for i in range(6)]
    assert stewart.platform_names == ["platform"]
    assert len(stewart.rod_names) == 6
    assert np.array_equal(stewart.default_inputs, np.full(6, 0.45))
    assert np.array_equal(stewart.input_lower, np.full(6, 0.2))
    assert np.array_equal(stewart.input_upper, np.full(6, 0.8))
    assert stewart.input_index("leg3") == 3
    assert np.array_equal(stewart.gravity, [0, 0, -9.81])


def test_missing_file_names_it():
    with pytest.raises(pcr.InputError, match="no_such_model.urdf"):
        pcr.load_model(model_path("no_such_model"))


def test_malformed_text_names_source_and_line():
    # A negative radius on the left rod's <section> line: the loader names source, line and value.
    text = open(model_path("planar_three_rod")).read()
    bad = text.replace('<section type="circle" radius="', '<section type="circle" radius="-', 1)
    assert bad != text
    with pytest.raises(pcr.InputError, match=r"my_robot\.urdf:\d+"):
        pcr.parse_model(bad, "my_robot.urdf")


def test_input_error_is_a_value_error(stewart):
    assert issubclass(pcr.InputError, ValueError)
    with pytest.raises(pcr.InputError, match="no_such_input"):
        stewart.input_index("no_such_input")


def test_pose_and_targets():
    p = pcr.Pose([0.0, 0.0, 0.4], [2.0, 0.0, 0.0, 0.0])  # normalised on construction
    assert np.array_equal(p.orientation, [1.0, 0.0, 0.0, 0.0])
    assert np.allclose(p.rotation(), np.eye(3))
    q = pcr.Pose.from_xyz_rpy([0, 0, 0], [0, 0, np.pi / 2])  # URDF yaw: x -> y
    assert np.allclose(q.rotation() @ [1, 0, 0], [0, 1, 0], atol=1e-15)
    t = pcr.LinkTarget("platform", "pose", ["x", "z", "ry"])
    assert t.mode == "pose" and t.components == ["x", "z", "ry"]
    with pytest.raises(pcr.InputError, match="'tilt'"):
        pcr.LinkTarget("platform", "pose", ["tilt"])
    with pytest.raises(pcr.InputError, match="'frame'"):
        pcr.LinkTarget("platform", "frame")
    with pytest.raises(pcr.InputError):
        pcr.Pose([0, 0, np.nan], [1, 0, 0, 0])
