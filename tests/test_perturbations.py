"""The perturbations a learned policy's errors are measured with: each does what it says on
a plain action, is drawn from its seed, and a bad one is refused in one line."""

import numpy as np
import pytest

from pyramid_sim.errors import ConfigError
from pyramid_sim.learning.evaluation.perturbations import OFFSET_PERIOD, Perturbation, Perturber

JOINTS = np.array([True, True, False])  # two joints and a finger gap


def _actions(n: int) -> list[np.ndarray]:
    return [np.array([0.01 * k, -0.01 * k, 0.05]) for k in range(n)]


def test_a_hold_repeats_each_kth_action_and_a_delay_lags_it():
    held = Perturber(Perturbation("hold", 3), JOINTS, 0)
    out = [held(a) for a in _actions(7)]
    assert [o[0] for o in out] == pytest.approx([0, 0, 0, 0.03, 0.03, 0.03, 0.06])
    late = Perturber(Perturbation("delay", 2), JOINTS, 0)
    out = [late(a) for a in _actions(5)]
    assert [o[0] for o in out] == pytest.approx([0, 0, 0, 0.01, 0.02])


def test_noise_and_offsets_touch_the_joints_only_and_are_drawn_from_the_seed():
    for kind in ("noise", "offset"):
        one = [Perturber(Perturbation(kind, 0.005), JOINTS, 7)(a) for a in _actions(3)]
        first = Perturber(Perturbation(kind, 0.005), JOINTS, 7)
        again = [first(a) for a in _actions(3)]
        assert np.array_equal(one[0], again[0])
        assert all(o[2] == 0.05 for o in again)  # the finger gap untouched
    offset = Perturber(Perturbation("offset", 0.005), JOINTS, 1)
    moved = [offset(a) - a for a in _actions(OFFSET_PERIOD + 1)]
    assert np.allclose(moved[0], moved[OFFSET_PERIOD - 1])  # held for a period
    assert not np.allclose(moved[0], moved[OFFSET_PERIOD])  # then redrawn
    assert 0 < np.abs(moved[0][:2]).max() < 0.03


def test_a_rows_name_gives_its_amount_in_the_actions_own_unit():
    """Joint actions' noise in mrad; a waypoint's in mm (the same numbers, metres)."""
    assert Perturbation("noise", 0.002).text == "noise 2 mrad"
    assert Perturbation("offset", 0.005, metres=True).text == "offset 5 mm"
    assert Perturbation("hold", 5, metres=True).text == "hold 5 steps"


@pytest.mark.parametrize(
    "kind, amount, says",
    [("shake", 1, "unknown 'shake'"), ("hold", 0, "accepted 1 or more"),
     ("delay", 2.5, "accepted 1 or more"), ("noise", -0.1, "accepted 0 to 10000")],
)  # fmt: skip
def test_a_bad_perturbation_is_refused_naming_what_is_accepted(kind, amount, says):
    with pytest.raises(ConfigError, match=says):
        Perturbation(kind, amount)
