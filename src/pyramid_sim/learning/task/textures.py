"""Procedural surface textures for visual randomization: a pattern drawn per surface (checker,
stripes, speckle or blotches) at a scale and contrast, around the surface's own tone, so its
material's colour still says what it is. Pure numpy: the randomizer writes the pixels into the
compiled model's textures."""

from __future__ import annotations

import numpy as np

PATTERNS = ("checker", "stripes", "speckle", "blotches")


def pattern(kind: str, cells: int, seed: int, height: int, width: int) -> np.ndarray:
    """A (height, width) field in [-1, 1]: `cells` squares, stripes or blotches across."""
    y, x = np.mgrid[0:height, 0:width]
    u, v = x / width, y / height
    rng = np.random.default_rng(seed)
    if kind == "checker":
        return ((np.floor(u * cells) + np.floor(v * cells)) % 2) * 2.0 - 1.0
    if kind == "stripes":
        return np.sin(2 * np.pi * (u * cells + 0.3 * np.sin(2 * np.pi * v)))
    if kind == "speckle":
        return rng.uniform(-1.0, 1.0, (height, width))
    if kind == "blotches":
        coarse = rng.uniform(-1.0, 1.0, (cells + 1, cells + 1))
        gu, gv = u * cells, v * cells  # bilinear over a coarse grid of random values
        i, j = np.floor(gu).astype(int), np.floor(gv).astype(int)
        fu, fv = gu - i, gv - j
        top = coarse[j, i] * (1 - fu) + coarse[j, i + 1] * fu
        bottom = coarse[j + 1, i] * (1 - fu) + coarse[j + 1, i + 1] * fu
        return top * (1 - fv) + bottom * fv
    raise ValueError(f"unknown pattern {kind!r}; accepted {', '.join(PATTERNS)}")


def texture_pixels(
    kind: str, cells: int, contrast: float, seed: int, base: np.ndarray, height: int, width: int
) -> np.ndarray:
    """(height, width, channels) uint8 pixels: `base` (per channel, 0-1) varied by the pattern
    with amplitude `contrast`."""
    field = pattern(kind, cells, seed, height, width)[..., None]
    return np.clip(base * (1.0 + contrast * field) * 255.0, 0, 255).round().astype(np.uint8)
