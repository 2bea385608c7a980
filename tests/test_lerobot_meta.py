"""The dataset's statistics kept as episodes land: merging episode by episode pools counts,
means and spreads exactly, and widens the quantiles to lerobot's envelope."""

from __future__ import annotations

import numpy as np

from pyramid_sim.learning.dataset.lerobot_format import _summary
from pyramid_sim.learning.dataset.lerobot_meta import aggregate, episodes_location, merge_stats


def _stats(values: np.ndarray) -> dict:
    return {"action": _summary(values) | {"count": np.array([len(values)])}}


def test_merging_episodes_gives_the_whole_datasets_count_mean_std_and_extremes():
    rng = np.random.default_rng(0)
    parts = [rng.normal(loc, 1.0, size=(n, 3)) for loc, n in ((0, 50), (5, 120), (-2, 7))]
    rows = [{"episode_index": i, "stats": _stats(p)} for i, p in enumerate(parts)]
    merged = aggregate(rows)["action"]
    whole = np.concatenate(parts)
    assert merged["count"].tolist() == [177]
    np.testing.assert_allclose(merged["mean"], whole.mean(axis=0), rtol=1e-12)
    np.testing.assert_allclose(merged["std"], whole.std(axis=0), rtol=1e-12)
    np.testing.assert_array_equal(merged["min"], whole.min(axis=0))
    np.testing.assert_array_equal(merged["max"], whole.max(axis=0))


def test_quantiles_widen_to_the_envelope_lower_ones_the_least_upper_the_greatest():
    low = _stats(np.arange(100.0)[:, None])
    high = _stats(np.arange(100.0, 300.0)[:, None])
    merged = merge_stats(merge_stats(None, low), high)["action"]
    assert merged["q01"].tolist() == low["action"]["q01"].tolist()
    assert merged["q50"].tolist() == low["action"]["q50"].tolist()
    assert merged["q90"].tolist() == high["action"]["q90"].tolist()
    assert merged["q99"].tolist() == high["action"]["q99"].tolist()


def test_an_episodes_row_lives_in_the_file_of_its_hundred():
    assert [episodes_location(e) for e in (0, 99, 100, 99_999)] == [
        (0, 0),
        (0, 0),
        (0, 1),
        (0, 999),
    ]
    assert episodes_location(100_000) == (1, 0)
