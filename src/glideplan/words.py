"""Type words: the run-length words of turn directions ("LSR") and family labels ("CBSB").

One labeller for every path representation: segments of an analytic path, samples of a
direct method's controls, the moves of a synthesis. A word is the sequence of runs of equal
letters; runs whose weight (arc length, time, turn angle) is below a threshold are dropped
first (zero-length segments, short blips of a sampled control), then equal neighbours merge.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["run_word", "turn_letters"]


def turn_letters(turn_rate: ArrayLike, tol: float = 0.0) -> np.ndarray:
    """'L' where turn_rate > tol (counter-clockwise), 'R' where < -tol, else 'S'."""
    u = np.asarray(turn_rate, dtype=float)
    return np.where(u > tol, "L", np.where(u < -tol, "R", "S"))


def run_word(
    letters: Iterable[str],
    weights: ArrayLike | None = None,
    *,
    min_weight: float = 0.0,
    strict: bool = False,
    keep_all_if_empty: bool = False,
) -> str:
    """The word of a sequence of letters (each a str of one or more letters) with weights.

    Consecutive equal letters form runs whose weights add up; runs lighter than `min_weight`
    (or not heavier, with `strict`) are dropped, then equal neighbours merge. With
    `keep_all_if_empty`, a word whose runs are all light keeps them all. Without weights every
    letter weighs 1. A letter given as several characters (the word of one segment) is
    spliced in.
    """
    seq: list[str] = [c for item in letters for c in str(item)]
    if weights is None:
        w: Sequence[float] = [1.0] * len(seq)
    else:
        w = [float(v) for v in np.asarray(weights, dtype=float).ravel()]
        if len(w) != len(seq):
            raise ValueError(f"{len(seq)} letters but {len(w)} weights")
    runs: list[list] = []
    for letter, weight in zip(seq, w, strict=True):
        if runs and runs[-1][0] == letter:
            runs[-1][1] += weight
        else:
            runs.append([letter, weight])
    kept = [r for r in runs if (r[1] > min_weight if strict else r[1] >= min_weight)]
    if not kept and keep_all_if_empty:
        kept = runs
    out: list[str] = []
    for letter, _ in kept:
        if not out or out[-1] != letter:
            out.append(letter)
    return "".join(out)
