"""A compiled phase's dense output: its step records (start state, nodal forcing, contact forces, summaries), evaluated
and searched in the kernels (``kernels/src/bookkeeping.c``, ``extremes.c``) only when outputs are asked for.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from .. import numerics as nm
from ..kernels import core

if TYPE_CHECKING:
    from .modal import ModalStepper

#: floats at the end of a step record that summarise the step (FB_RECORD_SUMMARY in kernels/src/phase.h): the total
#: and kinetic energy at its end, the tip deflection at its FB_P nodes; the float before them says which nodes
SUMMARY = 6
#: the Radau IIA nodes on (0, 1] and their weights, a resting contact's collocation (kernels/src/propagation.c:
#: x = 2 c - 1 the zeros of P_4(x) - P_3(x) and 1; weights (1 + x) / (32 P_3(x)^2) and 1/16; computed to 30 digits)
RADAU_NODES = np.array([0.088587959512703947395546143769456, 0.409466864440734710864926252068820,
                        0.787659461760847056025241889875996, 1.0])  # fmt: skip
RADAU_WEIGHTS = np.array([0.220462211176768375275478, 0.388193468843171880780232, 0.328844319980059743944289,
                          0.0625])  # fmt: skip


def gauss_nodes() -> tuple[np.ndarray, np.ndarray]:
    """The 4 Gauss-Legendre nodes and weights on (0, 1) of the collocation (every step but a resting contact's)."""
    x, w = nm.leggauss(4)
    return 0.5 * (x + 1.0), 0.5 * w


def radau_steps(records: np.ndarray) -> np.ndarray:
    """Which step records were collocated at Radau IIA's nodes (a resting contact's; the flag before the summary)."""
    return records[:, -SUMMARY - 1] != 0.0


def step_nodes(records: np.ndarray) -> np.ndarray:
    """Each step record's nodes on (0, 1] (steps x 4): Gauss's, or Radau's where :func:`radau_steps`."""
    c, _ = gauss_nodes()
    radau = radau_steps(records)
    if not radau.any():
        return np.broadcast_to(c, (records.shape[0], c.size))
    return np.where(radau[:, None], RADAU_NODES[None, :], c[None, :])


def step_quadrature(records: np.ndarray, values: np.ndarray) -> float:
    """sum over the steps of h x the step's quadrature of its nodal ``values`` (steps x 4), each step with its own
    nodes' weights (:func:`step_nodes`), the steps' terms summed correctly rounded (so grouped by node set freely)."""
    _, w = gauss_nodes()
    radau = radau_steps(records)
    h = records[:, 1]
    if not radau.any():
        return nm.fsum(h * nm.matmul(np.ascontiguousarray(values), w))
    gauss = ~radau
    parts = [h[gauss] * nm.matmul(np.ascontiguousarray(values[gauss]), w),
             h[radau] * nm.matmul(np.ascontiguousarray(values[radau]), RADAU_WEIGHTS)]  # fmt: skip
    return nm.fsum(np.concatenate(parts))


class ModalDense:
    """A phase's dense output from its step records (callable on an array of times, rows of states)."""

    def __init__(self, stepper: ModalStepper, records: np.ndarray) -> None:
        self.stepper, self.records = stepper, records

    @property
    def breaks(self) -> np.ndarray:
        """The step boundaries."""
        return np.append(self.records[:, 0], self.records[-1, 0] + self.records[-1, 1])

    @cached_property
    def ends(self) -> np.ndarray:
        """Each step's end time t0 + h (as the kernels compute it)."""
        return self.records[:, 0] + self.records[:, 1]

    def __call__(self, times: np.ndarray) -> np.ndarray:
        """States at ``times``: each in the first step that ends at or after it (the kernels' own choice), found by
        bisection, so an evaluation costs the steps it touches, not the phase's length."""
        times = np.ascontiguousarray(times, float)
        order = np.argsort(times, kind="stable")
        Y = np.empty((times.size, self.stepper.system.size))
        Ys = np.empty_like(Y)
        if times.size:
            ts = np.ascontiguousarray(times[order])
            nrec = self.records.shape[0]
            i0 = min(int(np.searchsorted(self.ends, ts[0], side="left")), nrec - 1)
            i1 = min(int(np.searchsorted(self.ends, ts[-1], side="left")) + 1, nrec)
            recs = self.records[i0:i1]
            core.dense(self.stepper.kernel, self.stepper.basis_buffer, recs, recs.shape[0], ts, Ys)
        Y[order] = Ys
        return Y

    def column_max(
        self, y0: np.ndarray, y1: np.ndarray, t0: float, t1: float, contacts: np.ndarray, column: int, sign: float,
        lo: np.ndarray, hi: np.ndarray, xtol: float, reach: np.ndarray | None = None, floor: float = -math.inf,
    ) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
        """Per bracket [lo_k, hi_k] of the phase [t0, t1] (exact states y0, y1 at its ends) the time and value of
        the largest ``sign`` x output column ``column`` (>= 0: :data:`~flexbeam.kernels.OUTPUT_COLUMNS`; < 0: the
        contact force of pair -1 - column) under the contacts buffer ``contacts``: Brent's method on the step's
        exact dense output, compiled (``kernels/src/extremes.c``; Brent 1973, ch. 5), to the absolute ``xtol``.
        ``reach``: a bound on each bracket's maximum; a bracket whose bound is below the best value found so far
        (or ``floor``) is skipped (time NaN, value -inf); give the brackets in decreasing order of their bounds."""
        lo = np.ascontiguousarray(lo, float)
        hi = np.ascontiguousarray(hi, float)
        reach = np.full(lo.size, math.inf) if reach is None else np.ascontiguousarray(reach, float)
        t_out, v_out = np.empty(lo.size), np.empty(lo.size)
        if lo.size:
            st = self.stepper
            core.column_max(
                st.kernel, st.basis_buffer, self.records, self.records.shape[0], contacts, float(t0), float(t1),
                np.ascontiguousarray(y0, float), np.ascontiguousarray(y1, float), int(column), float(sign), lo, hi,
                reach, float(floor), float(xtol), t_out, v_out,
            )  # fmt: skip
        return t_out, v_out

    def tip_slacks(self, y0: np.ndarray, y1: np.ndarray, t0: float, t1: float, times: np.ndarray) -> np.ndarray:
        """For each interval between consecutive ``times`` of the phase [t0, t1] (exact states y0, y1 at its ends), how
        far the tip's deflection can exceed the larger of its values at the interval's ends: the bound of
        ``kernels/src/tip_bound.c`` with T the interval's length (a derivation, no factor of safety)."""
        times = np.ascontiguousarray(times, float)
        out = np.empty(max(times.size - 1, 0))
        if times.size > 1:
            st = self.stepper
            core.tip_slacks(
                st.kernel, st.basis_buffer, self.records, self.records.shape[0], float(t0), float(t1),
                np.ascontiguousarray(y0, float), np.ascontiguousarray(y1, float), times, out,
            )  # fmt: skip
        return out

    def _forces(self, pair: int) -> np.ndarray:
        """A pair's nodal contact forces (steps x 4) of the records [t0, h, Ed0, W0, eta0, v0, f, F (pairs x 4),
        ...]."""
        N = self.stepper.basis.N
        off = 4 + 2 * N + 4 * N + 4 * pair
        return self.records[:, off : off + 4]

    def impulse(self, pair: int = 0) -> float:
        """int F dt of a pair over the phase: each step's quadrature (:func:`step_quadrature`) of its nodal contact
        force (or multiplier)."""
        return step_quadrature(self.records, self._forces(pair))

    def tangential_impulse(self, pair: int, sigma: float) -> float:
        """int F_t dt of a pair over the phase, F_t = sigma F + lambda_t: its slip's kinetic friction (``sigma``, 0
        unless it slips) and its nodal tangential unknown (a stick's multiplier, or the regularised law's force
        sigma(v_t) F: zero otherwise; ``kernels/src/nodal.c``), by each step's quadrature of the nodal values."""
        N, S = self.stepper.basis.N, self.stepper.system.pairs
        off = 4 + 6 * N + 4 * S + 8 + 4 * pair
        return sigma * self.impulse(pair) + step_quadrature(self.records, self.records[:, off : off + 4])

    def shared_tangential_impulse(self, holder: int, share: Callable[[np.ndarray], np.ndarray]) -> float:
        """int share lambda_t dt over the phase: a group's multiplier (its ``holder``'s, nodal) times a pair's share
        of it, ``share`` of the nodal normal forces (steps x 4 x pairs), by each step's quadrature of the nodal
        products (:mod:`flexbeam.results.friction`)."""
        N, S = self.stepper.basis.N, self.stepper.system.pairs
        off = 4 + 6 * N + 4 * S + 8 + 4 * holder
        F = np.stack([self._forces(k) for k in range(S)], axis=-1)
        return step_quadrature(self.records, self.records[:, off : off + 4] * share(F))

    def multipliers(self, pair: int, times: np.ndarray) -> np.ndarray:
        """A pair's tangential multiplier lambda_t (stick; zero otherwise) at ``times`` inside the phase: the Lagrange
        interpolant of its step's nodal values."""
        N, S = self.stepper.basis.N, self.stepper.system.pairs
        off = 4 + 6 * N + 4 * S + 8 + 4 * pair
        i = np.clip(np.searchsorted(self.records[:, 0], times, side="right") - 1, 0, self.records.shape[0] - 1)
        x = (np.asarray(times, float) - self.records[i, 0]) / self.records[i, 1]
        lam = self.records[i, off : off + 4]
        c = step_nodes(self.records[i])
        out = np.zeros(x.size)
        for j in range(4):
            lj = np.ones(x.size)
            for m in range(4):
                if m != j:
                    lj *= (x - c[:, m]) / (c[:, j] - c[:, m])
            out += lj * lam[:, j]
        return out

    def step_energies(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(each step's end time, the total energy T + V_e + V_g + U_c + E_d - W there, the kinetic energy there), as
        the integrator booked them for its energy balance (the last floats of a record, ``FB_RECORD_SUMMARY``)."""
        tail = self.records[:, -SUMMARY:]
        return self.ends, tail[:, 0], tail[:, 1]

    def tip_nodes(self) -> tuple[np.ndarray, np.ndarray]:
        """(times, values) of the tip deflection at every step's nodes, as the integrator evaluated it."""
        t = self.records[:, 0:1] + self.records[:, 1:2] * step_nodes(self.records)
        return t.ravel(), self.records[:, -SUMMARY + 2 :].ravel()

    def nodal_forces(self, pair: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """(times, values) of a pair's contact force (or multiplier) at every step's nodes."""
        t = self.records[:, 0:1] + self.records[:, 1:2] * step_nodes(self.records)
        return t.ravel(), self._forces(pair).ravel()
