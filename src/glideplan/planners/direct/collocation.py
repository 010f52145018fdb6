"""Collocation schemes and the NLP they transcribe (built once per mesh size, then reused).

The problem, in normalised time tau = t / T in [0, 1] with free final time T:
minimise J = integral_0^T L(c) dt subject to z' = (v cos psi + wx, v sin psi + wy, u)(z, c)
(wx, wy: a steady drift, an NLP parameter, zero unless given),
z(0) = 0, z(1) = goal (heading on a chosen 2 pi branch), c in the box, g(c) in [lo, hi].
Positions are scaled by `length_scale` and time by `time_scale` inside the NLP.

Schemes (Betts, *Practical Methods for Optimal Control*, 2010, sec. 4.6; Garg et al. 2010):

- "hermite-simpson" (separated controls): states at the mesh nodes, controls at the nodes
  and interval midpoints; midpoint states by cubic Hermite interpolation; Simpson defects
  and Simpson quadrature of the cost. Controls are piecewise quadratic.
- "radau" (flipped Legendre-Gauss-Radau, `degree` points per interval, the last at the
  interval end): states are polynomials of degree `degree` per interval, controls of degree
  `degree - 1`; the Radau quadrature integrates the cost.

Mesh interval fractions, goal and scales are NLP parameters, so one built solver serves every
start, goal and mesh distribution with the same number of intervals.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.planners.direct.system import ControlSystem
from glideplan.validation import check_integer

if TYPE_CHECKING:
    import casadi as ca

__all__ = ["SCHEMES", "Transcription", "build_transcription"]

SCHEMES = ("hermite-simpson", "radau")
N_STATES = 3


def _lagrange_basis(nodes: np.ndarray) -> list[np.polynomial.Polynomial]:
    basis = []
    for j, tj in enumerate(nodes):
        p = np.polynomial.Polynomial([1.0])
        for r, tr in enumerate(nodes):
            if r != j:
                p = p * np.polynomial.Polynomial([-tr, 1.0]) / (tj - tr)
        basis.append(p)
    return basis


def _lagrange_matrix(nodes: np.ndarray, at: np.ndarray) -> np.ndarray:
    """Matrix M with M[i, j] = l_j(at[i]) for the Lagrange basis on `nodes`."""
    return np.stack([p(at) for p in _lagrange_basis(nodes)], axis=-1)


@dataclass(frozen=True, eq=False)
class Transcription:
    """A built NLP for one system, scheme and number of intervals (see module docstring)."""

    system: ControlSystem
    scheme: str
    n_intervals: int
    degree: int
    solver: ca.Function
    n_state_points: int
    n_control_points: int
    lbg: np.ndarray
    ubg: np.ndarray
    rhs: ca.Function  # (z, c, Ls, Ts, drift) -> dz/dt in scaled units (per unit scaled time)
    kinematics: ca.Function  # c -> (speed, turn_rate)
    cost_rate: ca.Function  # c -> L
    path: ca.Function  # c -> path-constraint values
    radau_nodes: np.ndarray  # (degree,) collocation points in (0, 1] (radau only)
    objective: ca.Function  # (w, p) -> J, the cost without the smoothing penalty

    # ----- layout of the decision vector w = [T, vec(Z), vec(U)] -------------------------
    @property
    def n_variables(self) -> int:
        return 1 + N_STATES * self.n_state_points + self.system.n_controls * self.n_control_points

    def pack(self, T: float, Z: np.ndarray, U: np.ndarray) -> np.ndarray:
        """Decision vector from scaled final time, states (3, ns) and controls (m, nc)."""
        return np.concatenate([[T], np.asarray(Z).ravel(order="F"), np.asarray(U).ravel(order="F")])

    def unpack(self, w: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
        w = np.asarray(w, dtype=float).reshape(-1)
        ns, nc, m = self.n_state_points, self.n_control_points, self.system.n_controls
        Z = w[1 : 1 + N_STATES * ns].reshape((N_STATES, ns), order="F")
        U = w[1 + N_STATES * ns :].reshape((m, nc), order="F")
        return float(w[0]), Z, U

    # ----- where the points sit in normalised time ---------------------------------------
    def mesh(self, fractions: np.ndarray) -> np.ndarray:
        """Mesh node times tau_0 = 0 < ... < tau_N = 1 from interval fractions."""
        return np.concatenate([[0.0], np.cumsum(fractions)]) / float(np.sum(fractions))

    def state_tau(self, fractions: np.ndarray) -> np.ndarray:
        nodes = self.mesh(fractions)
        if self.scheme == "hermite-simpson":
            return nodes
        h = np.diff(nodes)
        inner = nodes[:-1, None] + h[:, None] * self.radau_nodes[None, :]
        return np.concatenate([[0.0], inner.ravel()])

    def control_tau(self, fractions: np.ndarray) -> np.ndarray:
        nodes = self.mesh(fractions)
        h = np.diff(nodes)
        if self.scheme == "hermite-simpson":
            mids = nodes[:-1] + 0.5 * h
            out = np.empty(2 * self.n_intervals + 1)
            out[0::2], out[1::2] = nodes, mids
            return out
        return (nodes[:-1, None] + h[:, None] * self.radau_nodes[None, :]).ravel()

    # ----- interpolation of a solution (warm starts and dense output) -------------------
    def interpolate(
        self,
        w: np.ndarray,
        fractions: np.ndarray,
        tau: np.ndarray,
        length_scale: float,
        time_scale: float,
        drift: tuple[float, float] = (0.0, 0.0),
    ) -> tuple[np.ndarray, np.ndarray]:
        """Scaled states (3, n) and controls (m, n) of a solution at normalised times tau.

        Uses the scheme's own interpolants: piecewise cubic Hermite states and quadratic
        controls (Hermite-Simpson), Lagrange polynomials (Radau).
        """
        T, Z, U = self.unpack(w)
        nodes = self.mesh(fractions)
        tq = np.clip(np.asarray(tau, dtype=float).reshape(-1), 0.0, 1.0)
        # Radau controls live on (tau_k, tau_k+1]: a mesh node belongs to the interval it ends
        side: Literal["left", "right"] = "left" if self.scheme == "radau" else "right"
        k = np.clip(np.searchsorted(nodes, tq, side=side) - 1, 0, self.n_intervals - 1)
        h = np.diff(nodes)[k]
        s = (tq - nodes[k]) / h
        if self.scheme == "hermite-simpson":
            u0, um, u1 = U[:, 2 * k], U[:, 2 * k + 1], U[:, 2 * k + 2]
            controls = u0 * (2 * s - 1) * (s - 1) + um * 4 * s * (1 - s) + u1 * s * (2 * s - 1)
            F = (
                np.asarray(
                    self.rhs(
                        Z, U[:, 0::2], length_scale, time_scale, np.asarray(drift, dtype=float)
                    ),
                    dtype=float,
                ).reshape(N_STATES, -1)
                * T
            )
            z0, z1, f0, f1 = Z[:, k], Z[:, k + 1], F[:, k] * h, F[:, k + 1] * h
            h00 = 2 * s**3 - 3 * s**2 + 1
            h10 = s**3 - 2 * s**2 + s
            h01 = -2 * s**3 + 3 * s**2
            h11 = s**3 - s**2
            states = h00 * z0 + h10 * f0 + h01 * z1 + h11 * f1
            return states, controls
        d = self.degree
        full = np.concatenate([[0.0], self.radau_nodes])
        Ls = _lagrange_matrix(full, s)  # (n, d+1)
        Lc = _lagrange_matrix(self.radau_nodes, s)  # (n, d)
        cols_z = k[:, None] * d + np.arange(d + 1)[None, :]
        cols_u = k[:, None] * d + np.arange(d)[None, :]
        states = np.einsum("inj,nj->in", Z[:, cols_z], Ls)
        controls = np.einsum("inj,nj->in", U[:, cols_u], Lc)
        return states, controls


DEFAULT_IPOPT = {
    "print_level": 0,
    "sb": "yes",
    "max_iter": 1000,
    "tol": 1e-9,
    "acceptable_tol": 1e-6,
    "mu_strategy": "adaptive",
}


def _model(ca: Any, system: ControlSystem) -> tuple[Any, ...]:
    """CasADi functions of the vehicle: rhs(z, c, Ls, Ts, drift) (scaled z'), kinematics(c)
    = (speed, turn rate), cost_rate(c), path(c) = g(c) with its bounds (lo, hi arrays), the
    number of path constraints."""
    m = system.n_controls
    c = ca.SX.sym("c", m)
    zs = ca.SX.sym("z", N_STATES)
    Ls_sym, Ts_sym = ca.SX.sym("Ls"), ca.SX.sym("Ts")
    speed, turn = system.kinematics(c)
    L = system.cost_rate(c)
    for what, expr in (("speed", speed), ("turn rate", turn), ("cost rate", L)):
        if not isinstance(expr, (ca.SX, ca.MX, ca.DM)) or expr.numel() != 1:
            raise InvalidParameterError(
                "system", system.name, f"its {what} must be one scalar CasADi expression"
            )
    W_sym = ca.SX.sym("drift", 2)  # steady uniform wind or current (m/s)
    wx, wy = W_sym[0], W_sym[1]
    rhs = ca.Function(
        "rhs",
        [zs, c, Ls_sym, Ts_sym, W_sym],
        [
            ca.vertcat(
                Ts_sym / Ls_sym * (speed * ca.cos(zs[2]) + wx),
                Ts_sym / Ls_sym * (speed * ca.sin(zs[2]) + wy),
                Ts_sym * turn,
            )
        ],
    )
    kin = ca.Function("kinematics", [c], [speed, turn])
    cost = ca.Function("cost_rate", [c], [L])
    pcs = list(system.path_constraints(c))
    pc_expr = ca.vertcat(*[e for e, _, _ in pcs]) if pcs else ca.SX(0, 1)
    pc_lo = np.array([float(lo) for _, lo, _ in pcs])
    pc_hi = np.array([float(hi) for _, _, hi in pcs])
    path = ca.Function("path", [c], [pc_expr])
    return rhs, kin, cost, path, pc_lo, pc_hi, len(pcs)


def _hermite_simpson(ca: Any, rhs: Any, cost: Any, N: int, m: int, T: Any, h: Any, Ls: Any,
                     Ts: Any, drift: Any) -> tuple[Any, Any, Any, Any, int, int]:
    """Z (states at N + 1 nodes), U (controls at nodes and midpoints), the Simpson defects
    and the Simpson quadrature J of the cost; the numbers of state and control points."""
    ns, nc = N + 1, 2 * N + 1
    Z = ca.SX.sym("Z", N_STATES, ns)
    U = ca.SX.sym("U", m, nc)
    Un, Um = U[:, 0::2], U[:, 1::2]
    F = T * rhs(Z, Un, Ls, Ts, drift)
    H3 = ca.repmat(h, N_STATES, 1)
    Zm = 0.5 * (Z[:, :-1] + Z[:, 1:]) + H3 / 8 * (F[:, :-1] - F[:, 1:])
    Fm = T * rhs(Zm, Um, Ls, Ts, drift)
    defects = Z[:, 1:] - Z[:, :-1] - H3 / 6 * (F[:, :-1] + 4 * Fm + F[:, 1:])
    Lk = cost(Un)
    Lmid = cost(Um)
    J = Ts * T * ca.sum2(h / 6 * (Lk[:, :-1] + 4 * Lmid + Lk[:, 1:]))
    return Z, U, defects, J, ns, nc


def _radau(ca: Any, rhs: Any, cost: Any, N: int, m: int, d: int, T: Any, h: Any, Ls: Any,
           Ts: Any, drift: Any) -> tuple[Any, Any, Any, Any, int, int, np.ndarray]:
    """Z, U, the Radau defects and quadrature J (degree d per interval); the numbers of state
    and control points and the Radau nodes in (0, 1]."""
    radau = np.array(ca.collocation_points(d, "radau"), dtype=float)
    full = np.concatenate([[0.0], radau])
    basis = _lagrange_basis(full)
    # C[r, j] = derivative of the r-th basis polynomial at collocation point j
    C = np.array([[basis[r].deriv()(radau[j]) for j in range(d)] for r in range(d + 1)])
    wq = np.array([p.integ()(1.0) - p.integ()(0.0) for p in _lagrange_basis(radau)])
    ns, nc = 1 + N * d, N * d
    Z = ca.SX.sym("Z", N_STATES, ns)
    U = ca.SX.sym("U", m, nc)
    H3 = ca.repmat(h, N_STATES, 1)
    cols = []
    J = ca.SX(0.0)
    Lall = cost(U)  # 1 x N d
    for j in range(d):
        zj = Z[:, j + 1 : j + 2 + (N - 1) * d : d]
        uj = U[:, j : j + 1 + (N - 1) * d : d]
        dz = 0
        for r in range(d + 1):
            dz = dz + C[r, j] * Z[:, r : r + 1 + (N - 1) * d : d]
        cols.append(dz - H3 * T * rhs(zj, uj, Ls, Ts, drift))
        J = J + wq[j] * ca.sum2(h * Lall[:, j : j + 1 + (N - 1) * d : d])
    return Z, U, ca.horzcat(*cols), Ts * T * J, ns, nc, radau


def _build(
    system: ControlSystem,
    scheme: str,
    n_intervals: int,
    degree: int,
    ipopt_options: tuple[tuple[str, object], ...] = (),
) -> Transcription:
    import casadi as ca  # heavy: imported when a direct solve is built

    m = system.n_controls
    N = n_intervals
    rhs, kin, cost, path, pc_lo, pc_hi, npc = _model(ca, system)
    T = ca.SX.sym("T")
    goal = ca.SX.sym("goal", N_STATES)
    frac = ca.SX.sym("frac", N)
    Ls, Ts, Js, smooth = ca.SX.sym("Ls"), ca.SX.sym("Ts"), ca.SX.sym("Js"), ca.SX.sym("eps")
    drift = ca.SX.sym("drift", 2)
    h = (frac / ca.sum1(frac)).T  # 1 x N
    radau = np.zeros(0)
    if scheme == "hermite-simpson":
        Z, U, defects, J, ns, nc = _hermite_simpson(ca, rhs, cost, N, m, T, h, Ls, Ts, drift)
    elif scheme == "radau":
        Z, U, defects, J, ns, nc, radau = _radau(ca, rhs, cost, N, m, degree, T, h, Ls, Ts,
                                                 drift)
    else:  # pragma: no cover - checked by the caller
        raise InvalidParameterError("scheme", scheme, f"must be one of {', '.join(SCHEMES)}")

    g_parts = [ca.vec(defects), Z[:, -1] - goal]
    lbg = [np.zeros(defects.numel()), np.zeros(N_STATES)]
    ubg = [np.zeros(defects.numel()), np.zeros(N_STATES)]
    if npc:
        G = path(U)  # npc x nc
        g_parts.append(ca.vec(G))
        lbg.append(np.tile(pc_lo, nc))
        ubg.append(np.tile(pc_hi, nc))
    w = ca.vertcat(T, ca.vec(Z), ca.vec(U))
    p = ca.vertcat(goal, frac, Ls, Ts, Js, smooth, drift)
    # A tiny penalty on control differences between consecutive collocation points picks
    # one control history where the cost does not fix it (singular arcs such as straight
    # Dubins segments would otherwise chatter between nodes and midpoints); it vanishes
    # like h for smooth controls and costs `smooth` * (jump / range)^2 per switch.
    rng = np.array(system.upper) - np.array(system.lower)
    rng = np.where(np.isfinite(rng) & (rng > 0), rng, 1.0)
    dU = (U[:, 1:] - U[:, :-1]) / ca.repmat(ca.DM(rng), 1, nc - 1)
    penalty = smooth * ca.sumsqr(dU)
    nlp = {"x": w, "p": p, "f": J / Js + penalty, "g": ca.vertcat(*g_parts)}
    objective = ca.Function("objective", [w, p], [J])
    opts: dict[str, Any] = {
        "print_time": False,
        "ipopt": {**DEFAULT_IPOPT, **dict(ipopt_options)},
    }
    solver = ca.nlpsol(f"direct_{scheme.replace('-', '_')}_{N}", "ipopt", nlp, opts)
    return Transcription(
        system=system, scheme=scheme, n_intervals=N, degree=degree, solver=solver,
        n_state_points=ns, n_control_points=nc, lbg=np.concatenate(lbg),
        ubg=np.concatenate(ubg), rhs=rhs, kinematics=kin, cost_rate=cost, path=path,
        radau_nodes=radau, objective=objective,
    )


@functools.lru_cache(maxsize=64)
def _cached(
    system: ControlSystem,
    scheme: str,
    n_intervals: int,
    degree: int,
    ipopt_options: tuple[tuple[str, object], ...],
) -> Transcription:
    return _build(system, scheme, n_intervals, degree, ipopt_options)


def build_transcription(
    system: ControlSystem,
    scheme: str,
    n_intervals: int,
    degree: int = 3,
    ipopt_options: tuple[tuple[str, object], ...] = (),
) -> Transcription:
    """The NLP for `system` on `n_intervals` mesh intervals (cached per system and size)."""
    if scheme not in SCHEMES:
        raise InvalidParameterError("scheme", scheme, f"must be one of {', '.join(SCHEMES)}")
    check_integer("n_intervals", n_intervals, 2)
    if scheme == "radau" and not (1 <= int(degree) <= 9):
        raise InvalidParameterError("degree", degree, "must be an integer in [1, 9]")
    deg = int(degree) if scheme == "radau" else 0
    opts = tuple(sorted((k, v) for k, v in ipopt_options if DEFAULT_IPOPT.get(k) != v))
    try:
        return _cached(system, scheme, int(n_intervals), deg, opts)
    except TypeError:  # an unhashable system or option value: build without caching
        return _build(system, scheme, int(n_intervals), deg, opts)
