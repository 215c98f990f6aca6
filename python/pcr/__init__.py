"""pcr: parallel continuum robots by isogeometric collocation.

SI units (m, rad, N, N m), world frame = the model's base link frame, quaternions [w, x, y, z].
Vectors and matrices are numpy arrays. Bad input raises pcr.InputError (a ValueError) with the message
of the C++ library (file, line, element and value where there is one); a solve that does not converge
is not an exception: its result's summary says why (result.summary.status, .message).

    import pcr
    model = pcr.load_model("models/stewart_gough.urdf")
    fk = pcr.ForwardKinematics(model)
    result = fk.solve({"leg0": 0.5})
    result.platforms[0].position, result.rods[0].centerline

See docs/python.md for the whole interface.
"""
from ._pcr import (  # noqa: F401
    InputError,
    Pose,
    LinkTarget,
    RobotModel,
    load_model,
    parse_model,
    SolveSummary,
    RodResult,
    Stability,
    RobotSolution,
    ForwardKinematics,
    InverseKinematics,
    WorkspaceSample,
    WorkspaceResult,
    sample_workspace,
)

__all__ = [
    "InputError", "Pose", "LinkTarget", "RobotModel", "load_model", "parse_model", "SolveSummary",
    "RodResult", "Stability", "RobotSolution", "ForwardKinematics", "InverseKinematics", "WorkspaceSample",
    "WorkspaceResult", "sample_workspace",
]
