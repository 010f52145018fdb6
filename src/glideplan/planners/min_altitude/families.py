"""The sufficient set of candidate controls (Theorem 5.7.1, extended) as a data table.

Each row is one class of extremal sequences with its orientations, the rule that fixes the
multiplier lambda, the arc-angle constraints and the solver that finds every member reaching
a goal. `glideplan.planners.min_altitude.synthesis.synthesize` walks this table; nothing
else enumerates families. Subsets with zero-length pieces (BS, SB, S of BSB; a zero first
or last arc of a B chain) appear as boundary solutions of their parent row.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["FAMILIES", "Family", "family_named"]


@dataclass(frozen=True)
class Family:
    """One row of the candidate table.

    Attributes:
        name: class name, e.g. "BSB", "BBB", "Bstall^4".
        words: the orientations (L/R per arc, S for the straight), first turn L or R.
        solver: "bsb" (all roots of a quartic), "chain" (2-D root finding over the switch
            angle and the first arc), "single_b" (2-D Newton from a linear solve) or
            "constant_speed" (algebraic).
        arcs: number of turning arcs (for "chain" and "constant_speed").
        speed: "v_stall" or "v_ms" for the constant-speed families.
        multiplier: the rule fixing lambda (the adjoint ratio eta / (2 eta0 a)).
        constraints: arc-angle limits enforced on every solution.
        source: the dissertation's lemmas and equations (and our extensions).
    """

    name: str
    words: tuple[str, ...]
    solver: str
    arcs: int
    speed: str = ""
    multiplier: str = ""
    constraints: str = ""
    source: str = ""


_CHAIN_RULE = (
    "lambda >= v_stf - v_ms; the switches sit where v = v_stf (H = 0), i.e. at "
    "phi = +-s with cos s = -(v_stf - v_ms)/lambda; speed clipped at v_stall when "
    "lambda > v_ms - v_stall"
)

FAMILIES: tuple[Family, ...] = (
    Family(
        "BSB",
        ("LSL", "LSR", "RSL", "RSR"),
        "bsb",
        2,
        multiplier="lambda = v_stf - v_ms (S flown at v_stf with psi = theta + pi)",
        constraints="0 <= |alpha|, |gamma| < 2 pi with the orientation's signs; L >= 0",
        source="Lemmas 5.6.6, 5.7.5, 5.7.9; (C.13)-(C.21)",
    ),
    Family(
        "BBBB",
        ("LRLR", "RLRL"),
        "chain",
        4,
        multiplier=_CHAIN_RULE,
        constraints="interior arcs turn exactly 2 s; first and last arcs in [0, 2 s]",
        source="Lemmas 5.7.8, 5.7.10-5.7.12 (+ H = 0 and clipping); (C.22)",
    ),
    Family(
        "BBB",
        ("LRL", "RLR"),
        "chain",
        3,
        multiplier=_CHAIN_RULE,
        constraints="interior arc turns exactly 2 s; first and last arcs in [0, 2 s]",
        source="Lemma 5.7.12 (+ H = 0 and clipping)",
    ),
    Family(
        "BB",
        ("LR", "RL"),
        "chain",
        2,
        multiplier=_CHAIN_RULE,
        constraints="both arcs in [0, 2 s], meeting at the switch phi = +-s",
        source="Lemma 5.7.12 (+ H = 0 and clipping)",
    ),
    Family(
        "B",
        ("L", "R"),
        "single_b",
        1,
        multiplier="any lambda >= 0 (theta free)",
        constraints="v <= v_stf along the arc (no switch inside: |phi| <= s when "
        "lambda > v_stf - v_ms); heading change psi1 mod 2 pi, or one more turn with at most "
        "one heading phi = pi (Lemma 5.7.7)",
        source="Lemma 5.7.12 (+ H = 0 and clipping)",
    ),
    Family(
        "Bms",
        ("L", "R"),
        "constant_speed",
        1,
        speed="v_ms",
        multiplier="eta = 0 (lambda = 0)",
        constraints="heading change in (0, 2 pi); joins no other extremal",
        source="Lemmas 5.6.5, 5.7.4; (C.9)-(C.12)",
    ),
    Family(
        "Bstall",
        ("L", "R"),
        "constant_speed",
        1,
        speed="v_stall",
        multiplier="eta0 = 0 (abnormal)",
        constraints="heading change < pi (cos(psi - theta) > 0 along the arc)",
        source="Lemmas 5.6.3, 5.7.3",
    ),
    Family(
        "Bstall^2",
        ("LR", "RL"),
        "constant_speed",
        2,
        speed="v_stall",
        multiplier="eta0 = 0 (abnormal)",
        constraints="both arcs in [0, pi]",
        source="Lemma 5.7.3; (C.28)",
    ),
    Family(
        "Bstall^3",
        ("LRL", "RLR"),
        "constant_speed",
        3,
        speed="v_stall",
        multiplier="eta0 = 0 (abnormal)",
        constraints="middle arc turns pi; first and last arcs in [0, pi]",
        source="Lemmas 5.7.2, 5.7.3; (C.27)",
    ),
    Family(
        "Bstall^4",
        ("LRLR", "RLRL"),
        "constant_speed",
        4,
        speed="v_stall",
        multiplier="eta0 = 0 (abnormal)",
        constraints="middle arcs turn pi; first + last < pi (total < 3 pi)",
        source="Lemmas 5.7.2, 5.7.3; (C.23)-(C.26)",
    ),
)


def family_named(name: str) -> Family:
    """The row of `FAMILIES` called `name`."""
    for fam in FAMILIES:
        if fam.name == name:
            return fam
    from glideplan.errors import InvalidParameterError

    known = ", ".join(f.name for f in FAMILIES)
    raise InvalidParameterError("family", name, f"must be one of {known}")
