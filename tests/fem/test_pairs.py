"""The FE reference's contact pairs: what it refuses, the side of the contact point."""

from __future__ import annotations

import pytest

from flexbeam.errors import ParameterError
from flexbeam.fem import simulate_fem
from tests.fem.cases import seed


@pytest.mark.parametrize(
    ("overrides", "field"),
    [
        ({"contact.anywhere": True}, "contact.anywhere"),
        ({"obstacle.support.stiffness": 1e6, "obstacle.support.mass": 0.1}, "obstacle.support"),
    ],
)
def test_unsupported_fields_raise_one_line_value_errors(overrides, field):
    case = seed(**{k.replace(".", "__"): v for k, v in overrides.items()})
    with pytest.raises(ValueError, match=f"^{field}: the FE reference supports") as err:
        simulate_fem(case)
    assert isinstance(err.value, ParameterError)
    assert "\n" not in str(err.value)


def test_a_contact_point_above_mirrors_one_below():
    """Without gravity, a contact point on the upper surface hit from below is the mirror image (y -> -y) of the
    seed's first contact: same peak force and duration to round-off (measured: identical; bound 1e-9; a side
    ignored would put P a beam depth away from the obstacle and give no contact or another force)."""
    below = simulate_fem(seed(solver__t_end=7e-4, model__gravity=0.0, fem__elements=16)).metrics()
    above = simulate_fem(
        seed(solver__t_end=7e-4, model__gravity=0.0, fem__elements=16, contact__side="above")
    ).metrics()
    assert above["contacts"] == below["contacts"] == 1
    for key in ("peak_force", "contact_duration"):
        assert above[key] == pytest.approx(below[key], rel=1e-9)
