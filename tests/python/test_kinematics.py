"""FK, IK, paths and derivatives from Python. The C++ reference is the pcr tool run on the same model
and inputs: its JSON has 17 significant digits (exact for a double), so the bindings must give the
same numbers bit for bit (same library, same options, same sequence of solves)."""
import os
import tempfile

import numpy as np
import pytest

import pcr
from conftest import model_path, run_tool


def test_fk_equals_the_tool_bit_for_bit(stewart):
    fk = pcr.ForwardKinematics(stewart)
    result = fk.solve({"leg0": 0.5})
    assert result.converged, result.summary.message
    ref = run_tool("fk", model_path("stewart_gough"), "--input", "leg0=0.5")
    assert ref["status"] == "converged"
    assert result.inputs.tolist() == [ref["inputs"]["leg%d" % i] for i in range(6)]
    assert result.platforms[0].position.tolist() == ref["platforms"]["platform"]["position"]
    assert result.platforms[0].orientation.tolist() == ref["platforms"]["platform"]["quaternion_wxyz"]
    for rod in result.rods:
        r = ref["rods"][rod.name]
        assert rod.centerline.shape == (21, 3)  # KinematicsOptions::centerline_points
        assert rod.centerline.tolist() == r["centerline"]
        assert rod.base_force.tolist() == r["base_wrench"]["force"]
        assert rod.tip_moment.tolist() == r["tip_wrench"]["moment"]
    J = fk.input_jacobian()
    C = fk.compliance("platform")
    assert J.tolist() == ref["input_jacobian"]["platform"]
    assert C.tolist() == ref["compliance"]["platform"]
    assert np.array_equal(fk.compliance(0), C)


def test_input_jacobian_matches_finite_differences(stewart):
    # Central differences of FK with h = 1e-6 m: truncation O(h^2 x third derivative) ~ 1e-12 and
    # rounding ~ tolerance / h ~ 1e-10 / 1e-6 relative: agreement to 1e-5 of the column's size.
    fk = pcr.ForwardKinematics(stewart)
    u = stewart.default_inputs.copy()
    u[2] = 0.47
    assert fk.solve(u).converged
    J = fk.input_jacobian()
    assert J.shape == (6, 6)
    h = 1e-6
    for i in (0, 2):
        plus, minus = u.copy(), u.copy()
        plus[i] += h
        minus[i] -= h
        probe = pcr.ForwardKinematics(stewart, tolerance=1e-13)
        xp = probe.solve(plus).platforms[0].position
        xm = probe.solve(minus).platforms[0].position
        column = (xp - xm) / (2 * h)
        assert np.linalg.norm(column - J[:3, i]) < 1e-5 * np.linalg.norm(J[:3, i])


def test_ik_round_trip(stewart):
    # FK at moved inputs, IK to the pose reached: the inputs come back. Both solves stop at 1e-10
    # dimensionless residuals (lengths scaled by ~0.5 m): 1e-9 m covers both.
    fk = pcr.ForwardKinematics(stewart)
    u = np.array([0.46, 0.44, 0.45, 0.47, 0.45, 0.43])
    reached = fk.solve(u)
    assert reached.converged
    ik = pcr.InverseKinematics(stewart, [pcr.LinkTarget("platform")])
    assert ik.square
    back = ik.solve([reached.platforms[0]])
    assert back.converged, back.summary.message
    assert np.max(np.abs(back.inputs - u)) < 1e-9


def test_ik_equals_the_tool_bit_for_bit(planar):
    target = [0.01, 0.0, 0.29]
    ik = pcr.InverseKinematics(planar, [pcr.LinkTarget("platform", "position")])
    result = ik.solve([pcr.Pose(target, [1, 0, 0, 0])])
    ref = run_tool("ik", model_path("planar_three_rod"), "--target", "platform=0.01,0,0.29")
    assert result.summary.status == ref["status"] == "converged"
    assert result.inputs.tolist() == [ref["inputs"][n] for n in planar.input_names]
    assert result.platforms[0].position.tolist() == ref["platforms"]["platform"]["position"]


def test_fk_path_equals_the_tool_path(stewart):
    rows = np.array([[0.45, 0.45], [0.46, 0.45], [0.47, 0.44]])  # leg0, leg1; the others at defaults
    inputs = np.tile(stewart.default_inputs, (3, 1))
    inputs[:, :2] = rows
    results = pcr.ForwardKinematics(stewart).solve_path(inputs)
    with tempfile.TemporaryDirectory() as tmp:
        csv = os.path.join(tmp, "legs.csv")
        with open(csv, "w") as f:
            f.write("leg0,leg1\n" + "".join("%r,%r\n" % tuple(r) for r in rows))
        ref = run_tool("path", model_path("stewart_gough"), "--inputs", csv)
    assert len(results) == len(ref["results"]) == 3
    for mine, theirs in zip(results, ref["results"]):
        assert mine.converged
        assert mine.platforms[0].position.tolist() == theirs["platforms"]["platform"]["position"]


def test_ik_path_is_warm_started(planar):
    ik = pcr.InverseKinematics(planar, [pcr.LinkTarget("platform", "position")])
    points = [[pcr.Pose([0.002 * k, 0.0, 0.29], [1, 0, 0, 0])] for k in range(4)]
    results = ik.solve_path(points)
    assert all(r.converged for r in results)
    for k, r in enumerate(results):  # position targets met to the IK tolerance (1e-10 x 0.3 m scale)
        assert np.max(np.abs(r.platforms[0].position - [0.002 * k, 0.0, 0.29])) < 1e-9
    # warm starts: the later points need fewer iterations than the cold first one
    assert max(r.summary.iterations for r in results[1:]) < results[0].summary.iterations


def test_bad_input_raises_with_the_message(stewart):
    fk = pcr.ForwardKinematics(stewart)
    with pytest.raises(pcr.InputError, match="no_such_leg"):
        fk.solve({"no_such_leg": 0.4})
    with pytest.raises(pcr.InputError, match="leg0"):
        fk.solve({"leg0": 5.0})  # above its upper bound 0.8 m
    with pytest.raises(pcr.InputError):
        fk.solve(np.zeros(3))  # 3 values for 6 inputs
    with pytest.raises(pcr.InputError, match="unknown option 'tolerence'"):
        pcr.ForwardKinematics(stewart, tolerence=1e-8)
    with pytest.raises(pcr.InputError, match="formulation='quadratic'"):
        pcr.ForwardKinematics(stewart, formulation="quadratic")
    with pytest.raises(pcr.InputError, match="no_such_link"):
        pcr.InverseKinematics(stewart, [pcr.LinkTarget("no_such_link")])
    with pytest.raises(pcr.InputError):
        fk.compliance(3)  # one platform


def test_unreachable_target_is_a_status_not_an_exception(planar):
    ik = pcr.InverseKinematics(planar, [pcr.LinkTarget("platform", "position")])
    result = ik.solve([pcr.Pose([0.0, 0.0, 5.0], [1, 0, 0, 0])])  # 5 m above rods of at most 0.5 m
    assert not result.converged
    assert result.summary.status != "converged" and result.summary.message


def test_stability_verdict_equals_the_tool(planar, stewart):
    # The tool's --stability JSON member and the binding's Stability are the same computation: the
    # verdicts and counts must agree (planar_three_rod's default pose tilts out of its plane: 1 unstable
    # mode; stewart_gough's default pose is stable - both asserted in C++ by test_stability_verdict).
    for model, name in ((planar, "planar_three_rod"), (stewart, "stewart_gough")):
        result = pcr.ForwardKinematics(model, stability_verdict=True).solve(model.default_inputs)
        ref = run_tool("fk", model_path(name), "--stability")["stability"]
        assert result.stability.verdict == ref["verdict"]
        assert result.stability.unstable_modes == ref["unstable_modes"]
        assert result.stability.margin == ref["margin"]
    assert pcr.ForwardKinematics(planar).solve(planar.default_inputs).stability.verdict == "not_checked"


def test_contacts_equal_the_tool_bit_for_bit():
    # planar_post: the middle rod presses on a post (docs/contact.md); same solve as the tool's.
    model = pcr.load_model(model_path("planar_post"))
    result = pcr.ForwardKinematics(model).solve(model.default_inputs)
    assert result.converged, result.summary.message
    ref = run_tool("fk", model_path("planar_post"))
    assert len(result.contacts) == len(ref["contacts"]) == 1
    for contact, r in zip(result.contacts, ref["contacts"]):
        assert (contact.rod, contact.obstacle) == (r["rod"], r["obstacle"])
        assert contact.force.tolist() == r["force"]
        assert np.linalg.norm(contact.force) > 0.0  # the rod does touch the post
        assert [contact.min_gap, contact.min_gap_arc_length] == [r["min_gap"], r["min_gap_arc_length"]]
        assert len(contact.intervals) == len(r["intervals"])
        for interval, ri in zip(contact.intervals, r["intervals"]):
            assert [interval.s_begin, interval.s_end] == [ri["s_begin"], ri["s_end"]]
            assert interval.force.tolist() == ri["force"]
        assert len(contact.arc_lengths) == len(contact.densities) == len(contact.gaps) > 0
        assert len(contact.forces) == len(contact.arc_lengths)
        # The cells' forces add up to the resultant the tool reports (sums of the same terms in another
        # order: round-off, 1e-12 of the force).
        total = np.sum(np.array(contact.forces), axis=0)
        assert np.linalg.norm(total - np.array(r["force"])) <= 1e-12 * np.linalg.norm(r["force"])
    assert len(result.contact_gaps) == len(ref["contact_gaps"]) == 1
    for gap, r in zip(result.contact_gaps, ref["contact_gaps"]):
        assert [gap.min_gap, gap.arc_length, gap.tolerance] == [r["min_gap"], r["arc_length"], r["tolerance"]]
