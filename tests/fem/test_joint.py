"""The FE reference takes the joint as the modal model describes it (:func:`flexbeam.model.joints.joint_of`):
the same drive and starting hub angle, and a joint kind it does not model refused by name."""

from __future__ import annotations

import pytest
from pydantic import BaseModel

from flexbeam.errors import ModelError
from flexbeam.fem import FemBeam, simulate_fem
from flexbeam.model import joints
from flexbeam.model.joints import RevoluteJoint, joint_of

from .cases import seed


@pytest.mark.parametrize(
    "overrides",
    [
        {},
        {"drive__kind": "torque", "drive__torque": -0.5},
        {"drive__kind": "prescribed", "drive__spin_rate": -0.8},
        {"drive__kind": "prescribed", "drive__profile": "kane-spinup", "drive__spin_rate": 1.0},
        {"drive__kind": "prescribed", "initial__kind": "state", "initial__angle": 0.2},
        {"drive__kind": "prescribed", "initial__kind": "release", "initial__release_angle": 0.1},
    ],
)
def test_the_fe_drive_is_the_joints_drive(overrides):
    case = seed(fem__elements=4, **overrides)
    beam = FemBeam.from_case(case)
    drive = joint_of(case).drive
    assert beam.drive == drive
    assert beam.drive.theta0 == drive.theta0
    assert beam.prescribed is joint_of(case).prescribed


class _Slider(RevoluteJoint):
    """A joint kind the FE reference does not model (a registry entry made for the test)."""

    kind = "slider"


def _slider_case():
    """The seed case with joint.kind = "slider", which the case's schema does not know: pydantic's own copy, which
    does not validate (the case's model_copy does)."""
    case = seed(fem__elements=4, solver__t_end=1e-4)
    return BaseModel.model_copy(case, update={"joint": BaseModel.model_copy(case.joint, update={"kind": "slider"})})


def test_an_unsupported_joint_kind_is_refused_by_name(monkeypatch):
    monkeypatch.setitem(joints.JOINTS, "slider", _Slider)
    case = _slider_case()
    assert joint_of(case).kind == "slider"  # the modal side has the kind
    with pytest.raises(ModelError, match=r"joint\.kind: .*'slider'"):
        FemBeam.from_case(case)
    with pytest.raises(ModelError, match="'slider'"):
        simulate_fem(case)
