"""The finite sufficient set (4.26) of minimum-time candidate types, as data.

Gamma = Gamma_TTTT (12 types x 2 orientations) + Gamma_TST (8 x 4) + Gamma_umax (4 x 2)
+ Gamma_Dubins (BSB and BBB at radius R, CCC at radius r): 72 candidate types.

Every non-Dubins type is a sequence of turns T(alpha, beta, gamma) = B^alpha C^beta B^gamma
(4.18-4.19), optionally with one straight S^L between the first two turns (Gamma_TST). A type
is described by its first piece (what is left of a turn after the start: "B", "CB" or "BCB"),
the number of interior (symmetric) turns, its last piece ("B", "BC" or "BCB") and the group;
the synthesis (`glideplan.planners.min_time.solvers`) walks this table.

Parameterisation. The dissertation leaves up to four parameters free per type and finds local
minima of (4.27) numerically. Using H = 0 along the extremal (4.12) fixes more of them, which
makes every type a square system with isolated solutions (re-derived here, see the module
`solvers` for the derivation):

- turn rate reversals and B/C switches happen at fixed headings relative to the adjoint
  direction theta: B <-> C where cos(psi - theta) = 0, so a C arc that is not cut by a
  boundary condition always subtends beta = pi;
- flexible turns (Gamma_TST, eta = eta0): the B arc next to the straight is pi/2 whenever a C
  arc follows it (B.3 gives the same result for beta; it leaves the B arc free);
- rigid turns (Gamma_TTTT, eta > eta0): all B arcs next to a reversal have the same angle
  a in (0, pi/2) (a -> pi/2 is the flexible limit, a -> 0 the C-only limit);
- fixed-turn-rate paths (Gamma_umax) are singular when the speed is not unique (eta = 0):
  every speed profile of the same heading change has the same time, so the group is solved as
  one convex reachability problem per orientation (B.1 case 4 dismisses this case because it
  drops kappa = u_max/v from H; with it, H = 0 for every speed).

A type's long-form parameters are, per turn, (alpha_i, beta_i, gamma_i) in terms of the free
parameters u1 (first piece), u2 (last piece), a (rigid) or L (straight):
first "B" = (0, 0, u1), "CB" = (0, u1, a), "BCB" = (u1, pi, a); interior = (a, pi, a);
last "B" = (u2, 0, 0), "BC" = (a, u2, 0), "BCB" = (a, pi, u2); with a = pi/2 in Gamma_TST.
The dissertation's conditions (4.20)-(4.24) and Table 4.2 are then checked on the solution
(`conditions`); the strict sub-optimality bounds (4.22) (alpha_subopt, B.12) and (4.24) (B.4)
are reported per candidate, not used to discard it.

Erratum. B.4 (hence (4.24) and the list Gamma_TTTT) drops rigid sequences in which an
interior turn has full B arcs on both sides. For some goals such a sequence, C B T B C, is the
optimum (confirmed by the direct method started from Dubins paths only), so the synthesis also
solves `SUPPLEMENTARY_TYPES` (`in_dissertation=False`); see `rigid_types`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = [
    "CANDIDATE_TYPES",
    "GROUPS",
    "SUPPLEMENTARY_TYPES",
    "CandidateType",
    "alpha_subopt",
    "conditions",
    "long_form",
    "rigid_types",
]

GROUPS = ("TTTT", "TST", "umax", "Dubins")

FIRST_PIECES = ("B", "CB", "BCB")
LAST_PIECES = ("B", "BC", "BCB")


@dataclass(frozen=True)
class CandidateType:
    """One candidate type of (4.26): group, extremal sequence, orientation and structure.

    `first`/`last` are the boundary pieces, `interior` the number of symmetric turns between
    them, `straight` whether an S segment joins the first and last turns (Gamma_TST).
    `faces` lists further (first, last) pieces that the dissertation's parameterisation of
    this type contains as a face (a zero-length arc) but that are separate pieces once H = 0
    is imposed (e.g. BBC inside BBCB). `directions` are the turn directions (+1 left).
    """

    group: str
    word: str
    orientation: str
    first: str = ""
    interior: int = 0
    last: str = ""
    straight: bool = False
    faces: tuple[tuple[str, str], ...] = ()
    directions: tuple[int, ...] = ()
    in_dissertation: bool = True

    @property
    def name(self) -> str:
        """e.g. 'CBSB LSR'."""
        return f"{self.word} {self.orientation}"

    @property
    def branches(self) -> tuple[tuple[str, str], ...]:
        """(first, last) piece pairs to solve: the type's own and its faces."""
        return ((self.first, self.last), *self.faces)


# (word, first piece, interior turns, last piece, faces) -- Gamma_TTTT (section 4.7)
_TTTT = (
    ("BTTB", "B", 2, "B", ()),
    ("BTBCB", "B", 1, "BCB", ()),
    ("BTBC", "B", 1, "BC", ()),
    ("BTB", "B", 1, "B", ()),
    ("BBCB", "B", 0, "BCB", (("B", "BC"),)),
    ("BCBTB", "BCB", 1, "B", ()),
    ("BCBBCB", "BCB", 0, "BCB", ()),
    ("BCBBC", "BCB", 0, "BC", ()),
    ("BCBB", "BCB", 0, "B", (("CB", "B"),)),
    ("CBTB", "CB", 1, "B", ()),
    ("CBBCB", "CB", 0, "BCB", ()),
    ("CBBC", "CB", 0, "BC", ()),
)

# (word, first piece, last piece) -- Gamma_TST (section 4.7)
_TST = (
    ("BCBSBCB", "BCB", "BCB"),
    ("BCBSBC", "BCB", "BC"),
    ("BCBSB", "BCB", "B"),
    ("CBSBCB", "CB", "BCB"),
    ("CBSBC", "CB", "BC"),
    ("CBSB", "CB", "B"),
    ("BSBCB", "B", "BCB"),
    ("BSBC", "B", "BC"),
)

# Gamma_umax (4.25): fixed turn rate, two simple turns of the same sense
_UMAX = ("BCBBCB", "BCBBC", "CBBCB", "CBBC")

# Gamma_Dubins: (word, Dubins words) -- BSB and BBB at radius R, CCC at radius r
_DUBINS = (
    ("BSB", ("LSL", "LSR", "RSL", "RSR")),
    ("BBB", ("LRL", "RLR")),
    ("CCC", ("LRL", "RLR")),
)


def _letters(directions: tuple[int, ...], straight: bool = False) -> str:
    s = ["L" if d > 0 else "R" for d in directions]
    if straight:
        s.insert(1, "S")
    return "".join(s)


def _build_table() -> tuple[CandidateType, ...]:
    out: list[CandidateType] = []
    for word, first, m, last, faces in _TTTT:
        for d1 in (1, -1):
            dirs = tuple(d1 * (-1) ** i for i in range(m + 2))
            out.append(
                CandidateType("TTTT", word, _letters(dirs), first, m, last, False, faces, dirs)
            )
    for word, first, last in _TST:
        for d1 in (1, -1):
            for d2 in (1, -1):
                dirs = (d1, d2)
                out.append(
                    CandidateType("TST", word, _letters(dirs, True), first, 0, last, True, (), dirs)
                )
    for word in _UMAX:
        for d in (1, -1):
            out.append(CandidateType("umax", word, _letters((d, d)), directions=(d, d)))
    for word, dubins_words in _DUBINS:
        for w in dubins_words:
            dirs = tuple(1 if c == "L" else -1 for c in w if c != "S")
            out.append(CandidateType("Dubins", word, w, directions=dirs))
    return tuple(out)


CANDIDATE_TYPES: tuple[CandidateType, ...] = _build_table()


def rigid_types(interior: int, *, skip_listed: bool = True) -> tuple[CandidateType, ...]:
    """Every rigid sequence (first piece, `interior` symmetric turns, last piece) not in (4.26).

    (4.24) and B.4 drop the sequences in which an interior turn has full B arcs on both sides
    (B T_RS B with equal arcs, said to be beaten by a single arc). That argument does not hold
    in general: for some goals the optimum is C B T B C (e.g. r/R = 0.5, goal (0.148, 0.786,
    2.347): CBTBC 5.4624 against 6.1080 for the best type of (4.26); the direct method
    started from Dubins paths only reaches 5.4626). These types are therefore solved too
    (`in_dissertation=False`).
    """
    listed = {(t.first, t.interior, t.last) for t in CANDIDATE_TYPES if t.group == "TTTT"}
    listed |= {(f, t.interior, la) for t in CANDIDATE_TYPES if t.group == "TTTT"
               for f, la in t.faces}  # fmt: skip
    out: list[CandidateType] = []
    for first in FIRST_PIECES:
        for last in LAST_PIECES:
            if skip_listed and (first, interior, last) in listed:
                continue
            if interior == 0 and first == last == "B":
                continue  # two B arcs: 2 parameters for 3 conditions, a Dubins path at most
            word = first + "T" * interior + last
            for d1 in (1, -1):
                dirs = tuple(d1 * (-1) ** i for i in range(interior + 2))
                out.append(
                    CandidateType(
                        "TTTT", word, _letters(dirs), first, interior, last, False, (), dirs, False
                    )
                )
    return tuple(out)


SUPPLEMENTARY_MAX_INTERIOR = 3
SUPPLEMENTARY_TYPES: tuple[CandidateType, ...] = tuple(
    t for m in range(SUPPLEMENTARY_MAX_INTERIOR + 1) for t in rigid_types(m)
)
"""Rigid sequences with at most three interior turns that (4.26) leaves out (see
`rigid_types`); the synthesis also adds longer ones when a path with m interior turns (cost
above m pi) could still beat the best found."""


def alpha_subopt(beta: float, rho: float) -> float:
    """(B.12): a symmetric turn B^a C^beta B^a with a >= alpha_subopt is sub-optimal.

    alpha_subopt = pi - beta/2 - asin(sin(beta/2) (R - r)/(R + r)), rho = r/R.
    """
    k = (1.0 - rho) / (1.0 + rho)
    return math.pi - 0.5 * beta - math.asin(math.sin(0.5 * beta) * k)


def long_form(
    ctype: CandidateType, first: str, last: str, u1: float, u2: float, a: float
) -> tuple[tuple[float, float, float], ...]:
    """Per-turn (alpha, beta, gamma) of a solution, from the free parameters (see module doc)."""
    pi = math.pi
    first_turn = {"B": (0.0, 0.0, u1), "CB": (0.0, u1, a), "BCB": (u1, pi, a)}[first]
    last_turn = {"B": (u2, 0.0, 0.0), "BC": (a, u2, 0.0), "BCB": (a, pi, u2)}[last]
    middle = ((a, pi, a),) * ctype.interior
    return (first_turn, *middle, last_turn)


def conditions(
    ctype: CandidateType, turns: tuple[tuple[float, float, float], ...], rho: float
) -> dict[str, bool]:
    """The dissertation's conditions on a solution's turns (True = satisfied).

    "4.20" heading change of each turn < 2 pi; "4.23" boundary-turn ordering (Table 4.2:
    |alpha1| <= |gamma1| at the start, |gamma_n| <= |alpha_n| at the end); "4.22"
    min(|alpha_i|, |gamma_i|) < alpha_subopt(beta_i) (B.12) for turns with a C arc; "4.24"
    min(|gamma_i|, |alpha_k|) < |alpha_j| for three consecutive turns (B.4).
    """
    tol = 1e-9
    out = {"4.20": all(sum(t) < 2.0 * math.pi - tol for t in turns)}
    out["4.23"] = turns[0][0] <= turns[0][2] + tol and turns[-1][2] <= turns[-1][0] + tol
    out["4.22"] = all(min(al, ga) < alpha_subopt(be, rho) - tol for al, be, ga in turns if be > tol)
    if ctype.group == "TTTT":
        out["4.24"] = all(
            min(turns[i][2], turns[i + 2][0]) < turns[i + 1][0] - tol for i in range(len(turns) - 2)
        )
    return out
