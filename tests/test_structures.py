"""The generators reproduce DE NIRO's numbers (the pick_and_place.py of its pyramid)."""

import pytest

from pyramid_sim import (
    ConfigError,
    create_coordinates,
    create_coordinates_new,
    pyramid,
    pyramid_even,
)
from pyramid_sim.core.seed_pyramids import SEED_GAP


def test_de_niros_create_coordinates_numbers():
    lay, start = create_coordinates(4)
    assert start == [0.49, 0.01, 0.11]
    # Worked by hand from DE NIRO's code: x = 0.49 + 0.192 + 0.05; y = 0.01 + item * (0.086 + 0.03);
    # z = 0.11 + (4 - j - 1) * 0.062 + 0.03, top layer (j = 0) first.
    assert lay[0] == [0.732, 0.01, 0.326]
    assert lay[1:3] == [[0.732, -0.048, 0.264], [0.732, 0.068, 0.264]]
    assert lay[3:6] == [[0.732, -0.106, 0.202], [0.732, 0.01, 0.202], [0.732, 0.126, 0.202]]
    assert lay[6:] == [
        [0.732, -0.164, 0.14],
        [0.732, -0.048, 0.14],
        [0.732, 0.068, 0.14],
        [0.732, 0.184, 0.14],
    ]


def test_de_niros_create_coordinates_new_numbers():
    lay, _ = create_coordinates_new(4)
    assert [len([p for p in lay if p[2] == z]) for z in (0.14, 0.202, 0.264, 0.326)] == [8, 6, 4, 2]
    assert lay[0] == [0.732, -0.396, 0.14]
    assert lay[7] == [0.732, 0.416, 0.14]
    assert lay[-2:] == [[0.732, -0.048, 0.326], [0.732, 0.068, 0.326]]


@pytest.mark.parametrize(
    "generator, de_niros", [(pyramid, create_coordinates), (pyramid_even, create_coordinates_new)]
)
@pytest.mark.parametrize("layers", [1, 2, 3, 4, 5])
def test_targets_are_de_niros_coordinates_less_the_release_gap(generator, de_niros, layers):
    targets = generator(layers)
    mine = sorted(
        (round(t.pose.x, 4), round(t.pose.y, 4), round(t.pose.z + SEED_GAP, 4)) for t in targets
    )
    theirs = sorted(tuple(p) for p in de_niros(layers)[0])
    assert mine == theirs
    assert all(t.pose.yaw == 0.0 for t in targets)  # long axis away from the robots


def test_layers_count_from_the_bottom():
    targets = pyramid(4)
    assert [sum(t.layer == k for t in targets) for k in range(4)] == [4, 3, 2, 1]
    assert min(t.pose.z for t in targets if t.layer == 0) == pytest.approx(0.11)
    assert min(t.pose.z for t in targets if t.layer == 3) == pytest.approx(0.11 + 3 * 0.062)


def test_pyramid_layers_are_offset_by_half_a_pitch():
    targets = pyramid(3)
    bottom = sorted(t.pose.y for t in targets if t.layer == 0)
    middle = sorted(t.pose.y for t in targets if t.layer == 1)
    assert middle[0] - bottom[0] == pytest.approx((0.086 + 0.03) / 2)


@pytest.mark.parametrize("bad", [0, -1, 13, 2.5, "3", True])
def test_bad_layer_counts_are_refused(bad):
    with pytest.raises(ConfigError, match="layers"):
        pyramid(bad)
