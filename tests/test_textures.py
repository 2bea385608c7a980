"""The randomizer's procedural textures: each pattern a field in [-1, 1] at the scale asked,
the pixels around the surface's tone, the same from the same seed."""

import numpy as np
import pytest

from pyramid_sim.learning.task.textures import PATTERNS, pattern, texture_pixels


@pytest.mark.parametrize("kind", PATTERNS)
def test_each_pattern_is_a_varied_field_in_range_repeated_by_its_seed(kind):
    field = pattern(kind, 4, 11, 32, 48)
    assert field.shape == (32, 48) and field.min() >= -1.0 and field.max() <= 1.0
    assert field.std() > 0.1
    np.testing.assert_array_equal(field, pattern(kind, 4, 11, 32, 48))


def test_a_checker_has_the_cells_asked_for():
    row = pattern("checker", 4, 0, 8, 64)[0]
    assert np.count_nonzero(np.diff(row)) == 3  # 4 cells across: 3 edges


def test_pixels_vary_around_the_base_tone_by_the_contrast():
    base = np.array([0.5, 0.4, 0.3])
    pixels = texture_pixels("speckle", 4, 0.2, 3, base, 64, 64).astype(float) / 255.0
    assert pixels.shape == (64, 64, 3)
    np.testing.assert_allclose(pixels.mean(axis=(0, 1)), base, atol=0.01)
    assert np.all(pixels <= base * 1.2 + 0.003) and np.all(pixels >= base * 0.8 - 0.003)
    with pytest.raises(ValueError, match="unknown pattern 'waves'"):
        pattern("waves", 4, 0, 8, 8)
