"""The production integrator: exact modal propagation with Gauss collocation, compiled (``flexbeam.kernels``).

Linearising M(z) z'' = Q + J^T F about the undeformed beam at rest gives M0 z'' + K0 z = R; in the modal
coordinates z = Psi eta of (K0, M0) each mode is propagated exactly over a step for a polynomial forcing and the
remainder R (mass-matrix variation, centrifugal stiffening, Coriolis, gravity, drive, contact) is collocated at
four Gauss nodes (``kernels/src/collocation.c``).  In the system frame (the default for a free or torque-driven
joint, ``docs/formulation.md``) M0 = diag(J_c, mu L I) and K0 = diag(0, K_ff) are diagonal, so Psi is a diagonal
scaling and the remainder is small and smooth: free flight takes long steps, a contact ~20-40.  A compliant
support adds its coordinate sqrt(m_s) s as one more mode of frequency sqrt(k_s / m_s).

The whole step loop of a phase -- steps, step control, the guaranteed event search and location -- runs in
compiled code (``kernels/src/phase.c``); each accepted step is recorded (start state, nodal forcing) as the
phase's dense output, evaluated only when outputs are asked for.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .. import numerics as nm
from ..kernels import SWITCH_HELD, SWITCH_REBOUND, core, pack_controls
from ..model.system import BeamSystem
from .dense import ModalDense
from .loop import PhaseRun, Switch
from .modal_basis import ModalBasis
from .phases import EventKind, Phase

FIRST_STEP = 1e-5  # [s] first step of a phase (the controller grows it by up to 5x per step)
_ADV_END, _ADV_EVENT, _ADV_FULL, _ADV_UNDERFLOW, _ADV_NONFINITE, _ADV_STALLED, _ADV_JUMPING = 0, 1, 2, 3, 4, 5, 6
_ADV_STOPPED = -1  # (Python's own: the phase ends where the kernel handed back, the run's ``stop`` asked for it)
_FAILURES = (_ADV_UNDERFLOW, _ADV_NONFINITE, _ADV_STALLED, _ADV_JUMPING)  # the codes that fail the run
#: the kernel's info row (``phase.h``): [event kind, steps, rejected, node evaluations, event pair, phase start,
#: rejections by cause (_REJECT_CAUSES, in order), the step taken at the event before it was cut to end there, then
#: a pair anywhere's jumps: their count in the window, its start, the last one's pair and material coordinates]
_INFO_T0, _INFO_REJECT = 5, 6
_REJECT_CAUSES = ("error estimate", "energy balance", "collocation not converging", "event search undecided")
_INFO_STEP = _INFO_REJECT + len(_REJECT_CAUSES)
_INFO_JUMPS, _JUMP_FIELDS = _INFO_STEP + 1, 5
_INFO_SIZE = _INFO_JUMPS + _JUMP_FIELDS
#: EventKind by the kernel's code (a tuple look-up: the enum's call costs microseconds)
_EVENT_KINDS = (None, *EventKind)
#: the event bits of a phase's events tuple, filled as met
_EVENT_MASKS: dict[tuple, int] = {}
#: the control buffer's bit (among the event bits) for a phase collocated at Radau IIA's nodes (FB_CTRL_RADAU)
_RADAU_BIT = 128
_EVENT_BITS = {EventKind.IMPACT: 1, EventKind.SEPARATION: 2, EventKind.RELEASE: 4, EventKind.STOP: 8,
               EventKind.UNSTICK_PLUS: 16, EventKind.UNSTICK_MINUS: 32, EventKind.PAINLEVE: 64}  # fmt: skip
#: the largest block of step records the kernel fills in one call (the blocks grow from 64 by doubling); a stepper
#: that hands on (a streamed run) hands a phase on in parts of at least this many records (13 MB for the seed case).
#: The kernel resumes a phase from its state buffer after each block (the nodal forcing, and a held constraint's
#: largest multiplier so far, which scales its multiplier's error): the steps are those of one long call, whatever
#: the block size
BLOCK_RECORDS = 16384
#: a switch row's floats before its modal state and the rule's record values after it (FB_SWITCH_HEAD, _JUMP:
#: ``kernels/src/phase.h``), and the switches one kernel call takes at most before it hands the event on
_SWITCH_HEAD, _SWITCH_JUMP, _SWITCH_ROWS = 14, 6, 64


def stalled_message(phase: str, t1: float, h: float, info: np.ndarray) -> str:
    """The failure of a phase that exhausted its step budget (``EFFORT_*`` in ``kernels/src/phase.c``): where it
    stopped, how little its attempts advanced it and why its steps were rejected, the most frequent cause first."""
    t0, steps, rejected = float(info[_INFO_T0]), int(info[1]), int(info[2])
    causes = sorted(zip(info[_INFO_REJECT:], _REJECT_CAUSES), key=lambda c: -c[0])
    why = ", ".join(f"{int(n)} by the {name}" for n, name in causes if n) or "none"
    return (
        f"no progress at t = {t1:.9g} s ({phase} phase): {steps + rejected} step attempts advanced the phase "
        f"{t1 - t0:.3g} s from t = {t0:.9g} s, the step size now {h:.3g} s; {rejected} rejected ({why})"
    )


def jumping_message(phase: str, t1: float, jumps: np.ndarray) -> str:
    """The failure of a phase whose pair anywhere's contact point kept jumping (``JUMP_*`` in
    ``kernels/src/jumps.c``): ``jumps`` the kernel's count, window start, pair and the last jump's two points."""
    count, start, pair, x0, x1 = jumps
    return (
        f"events keep recurring without progress at t = {t1:.9g} s ({phase} phase): the contact point of pair "
        f"{int(pair)} jumped {int(count)} times within {t1 - start:.2g} s between x = {x0:.4g} m and x = {x1:.4g} m "
        "of the beam, which touches that surface at both at once"
    )


class ModalStepper:
    """Advances phases of one system with the compiled collocation integrator."""

    name = "exponential modal Gauss collocation (p = 4), compiled, event-driven"

    def __init__(
        self, system: BeamSystem, rtol: float = 1e-6, atol: float = 1e-9, max_step: float | None = None
    ) -> None:
        self.system = system
        self.rtol, self.atol = rtol, atol
        self.max_step = max_step or math.inf
        self.basis = ModalBasis.of(system)
        self.basis_buffer = self.basis.packed()
        self.kernel = system.kernel
        self.record_size, self.state_size, _, _, _ = core.sizes(self.basis.N, system.pairs)
        self.h = FIRST_STEP
        #: the step the controller took where the last phase ended (before it was cut to end at its event)
        self.h_taken = FIRST_STEP
        self.omega_rigid = self.basis.omega_rigid
        self.psi = np.diag(self.basis.Psi).copy() if self.basis.diagonal else None
        self.to_m = np.diag(self.basis.toM).copy() if self.basis.diagonal else None
        #: set by a streamed run's loop: called with each finished part of a long phase (t0, y0, t1, y1, dense,
        #: opens), which is then dropped (:func:`flexbeam.integrate.loop.run_phases`)
        self.hand_on = None
        #: set by the loop of a run that may be stopped: asked between blocks of steps for a cause to end the phase
        #: there ("" goes on; :func:`flexbeam.integrate.loop.run_phases`)
        self.stop = None
        #: the impact method whose switches the kernel takes itself (kernels/src/switching.c: its ``switch_coef``
        #: and ``switched_phase``, :mod:`flexbeam.methods.switches`); None: the phase loop takes them all
        self.switching = None
        self._modes: tuple = ()  # the contact modes of the last phase advanced

    # state conversion between the reference layout [z, z', (s, s'), E_d, W] and modal (eta, v)
    def to_modal(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        N = self.basis.N
        eta, v = np.empty(N), np.empty(N)
        self._put_modal(y, eta, v)
        return eta, v

    def _put_modal(self, y: np.ndarray, eta: np.ndarray, v: np.ndarray) -> None:
        """Write the modal coordinates and velocities (eta, v) of state ``y`` into the arrays ``eta``, ``v``."""
        nz, N = self.system.nz, self.basis.N
        if self.to_m is not None and N == nz:  # a diagonal basis (the system frame): no matrix product
            np.multiply(self.to_m, y[:nz], out=eta)
            np.multiply(self.to_m, y[nz : 2 * nz], out=v)
            return
        z, zd = np.empty(N), np.empty(N)
        z[:nz], zd[:nz] = y[:nz], y[nz : 2 * nz]
        if N > nz:
            z[nz], zd[nz] = y[2 * nz], y[2 * nz + 1]
        if self.to_m is not None:
            np.multiply(self.to_m, z, out=eta)
            np.multiply(self.to_m, zd, out=v)
        else:
            eta[:], v[:] = nm.matmul(self.basis.toM, z), nm.matmul(self.basis.toM, zd)

    def from_modal(self, eta: np.ndarray, v: np.ndarray, Ed: float, W: float) -> np.ndarray:
        nz, N = self.system.nz, self.basis.N
        if self.psi is not None and N == nz:  # a diagonal basis without a support's mode: straight into y
            y = np.empty(self.system.size)
            np.multiply(self.psi, eta, out=y[:nz])
            np.multiply(self.psi, v, out=y[nz : 2 * nz])
            y[-2], y[-1] = Ed, W
            return y
        if self.psi is not None:
            z, zd = self.psi * eta, self.psi * v
        else:
            z, zd = nm.matmul(self.basis.Psi, eta), nm.matmul(self.basis.Psi, v)
        y = np.empty(self.system.size)
        y[:nz], y[nz : 2 * nz] = z[:nz], zd[:nz]
        if N > nz:
            y[2 * nz], y[2 * nz + 1] = z[nz], zd[nz]
        y[-2], y[-1] = Ed, W
        return y

    def advance(self, phase: Phase, t: float, y: np.ndarray, t_end: float) -> PhaseRun:
        N = self.basis.N
        state = np.zeros(self.state_size)
        self._put_modal(y, state[5 : 5 + N], state[5 + N : 5 + 2 * N])
        # a contact starts with a short step (the force grows as d^n from zero: not polynomial at the onset),
        # free flight where the last phase left off; the controller grows either by up to 5x per step
        # (a friction event -- the same pairs in contact, the friction switched -- keeps the step the controller took
        # there, not the step cut to end at the event: no new contact, and a stick's residual slip decays over its
        # first step (kernels/src/nodal.c) -- over a cut step of 1e-9 s its multiplier ~ m v_t / h broke the stick at
        # once, and the switches recurred at ever shorter intervals down to a step-size underflow)
        switched = phase.friction is not None and self._modes == phase.modes
        if switched:
            h = self.h_taken
        else:
            h = min(self.h, FIRST_STEP) if phase.in_contact else self.h
        self._modes = phase.modes
        state[:5] = t, h, y[-2], y[-1], 0.0
        # the phase's step bound holds up to phase.max_step_until (an impact's force pulse); the rest of the phase
        # continues from the same state buffer (its nodal forcing the guess) under the stepper's own bound alone -- all
        # of a phase that starts past it (a friction event's, or another pair's separation, in an old contact)
        # -- and collocates at Radau IIA's nodes after it (a contact under its law that has outlasted its impact: a
        # resting contact, whose spring the step no longer resolves; kernels/src/propagation.c, fb_radau)
        until = phase.max_step_until
        rests = math.isfinite(until)
        if t < until:
            legs = [(min(self.max_step, phase.max_step), min(until, t_end), False)]
            if until < t_end:
                legs.append((self.max_step, t_end, rests))
        else:
            legs = [(self.max_step, t_end, rests)]
        chunks: list[np.ndarray] = []
        handed = _Handed(float(t), np.array(y, float))
        # the friction switches the kernel takes (rows of the switch buffer), with the steps and node evaluations of
        # the part of the phase each ends; steps, nfev: the part after the last one
        handed.coef = self._switching(phase)
        switches: list[tuple[int, np.ndarray, int, int]] = []
        steps, nfev = 0, 0
        info = np.empty(_INFO_SIZE)
        ctrl = None
        for hmax, leg_end, radau in legs:
            if ctrl is None:
                ctrl = self._controls(phase, hmax)
            else:  # (the friction rows as the kernel left them)
                ctrl = ctrl.copy()
                ctrl[2] = hmax
            if radau:
                ctrl[4] = float(int(ctrl[4]) | _RADAU_BIT)
            info.fill(0.0)
            info[_INFO_T0] = state[0]  # the kernel sets it only at the phase's start (its effort budget)
            code = self._run(ctrl, state, leg_end, info, chunks, handed)
            for start, row in handed.switched:
                switches.append((start, row, steps + int(row[9]), nfev + int(row[10])))
                steps = nfev = 0
            handed.switched.clear()
            steps, nfev = steps + int(info[1]), nfev + int(info[3])
            if code != _ADV_END:
                break
        t1 = float(state[0])
        self.h = float(state[1])
        self.h_taken = float(info[_INFO_STEP]) if code == _ADV_EVENT else self.h
        y1 = self.from_modal(state[5 : 5 + N], state[5 + N : 5 + 2 * N], state[2], state[3])
        dense = None
        if chunks:  # (one block, the common case: its rows copied, as the concatenation of several blocks would)
            dense = ModalDense(self, chunks[0].copy() if len(chunks) == 1 else np.concatenate(chunks))
        parts: list[Switch] = []
        if switches:
            parts, dense = self._split(dense, switches)
        event = _EVENT_KINDS[int(info[0])] if code == _ADV_EVENT else None
        failure = ""
        if parts and code in _FAILURES:  # (the message names the phase at the end, its advice reads its rows)
            for sw in parts:
                phase = self.switching.switched_phase(phase, sw)
        if code == _ADV_UNDERFLOW:
            failure = f"step size underflow at t = {t1:.9g} s ({phase.name} phase)" + phase.underflow_advice
        elif code == _ADV_NONFINITE:
            failure = f"non-finite state at t = {t1:.9g} s ({phase.name} phase)"
        elif code == _ADV_STALLED:
            failure = stalled_message(phase.name, t1, float(state[1]), info)
        elif code == _ADV_JUMPING:
            failure = jumping_message(phase.name, t1, info[_INFO_JUMPS : _INFO_JUMPS + _JUMP_FIELDS])
        run = PhaseRun(t1, y1, event, dense, steps, nfev, failure, int(info[4]), switches=parts)
        if handed.start is not None:
            run.t0, run.y0 = handed.start
        return run

    def _switching(self, phase: Phase) -> np.ndarray | None:
        """The ``coef`` of the switches the kernel takes in ``phase`` (the method's, CCM's and IMM's with this
        stepper's step bounds and first step), or None where the phase loop takes them: a diagonal basis only (the
        kernel passes the state through y = Psi eta as :meth:`from_modal` does), not handed on in parts (streamed)."""
        if self.switching is None or self.hand_on is not None or self.psi is None:
            return None
        coef = self.switching.switch_coef(phase)
        if coef is not None and coef[0] in (SWITCH_HELD, SWITCH_REBOUND):  # the phases' bounds as advance takes them
            coef[5], coef[6], coef[7] = min(self.max_step, coef[5]), min(self.max_step, coef[6]), FIRST_STEP
        return coef

    def _split(self, dense: ModalDense, switches: list) -> tuple[list[Switch], ModalDense | None]:
        """The phase's records cut where the kernel switched: a :class:`~flexbeam.integrate.loop.Switch` for the
        part before each switch, and the dense output of the part after the last."""
        N, records, parts, a = self.basis.N, dense.records, [], 0
        for start, row, steps, nfev in switches:
            mid, tail = _SWITCH_HEAD + 2 * N, _SWITCH_HEAD + 2 * N + _SWITCH_JUMP  # (eta, v) before mid
            y = self.from_modal(row[_SWITCH_HEAD : _SWITCH_HEAD + N], row[_SWITCH_HEAD + N : mid], row[12], row[13])
            part = ModalDense(self, records[a:start]) if start > a else None
            parts.append(Switch(float(row[1]), y, _EVENT_KINDS[int(row[2])], int(row[3]), row[4:9].copy(), part,
                                steps, nfev, row[mid:tail].copy(), row[tail:].copy()))  # fmt: skip
            a = start
        return parts, ModalDense(self, records[a:]) if records.shape[0] > a else None

    def _controls(self, phase: Phase, hmax: float) -> np.ndarray:
        """The control buffer of ``phase`` under the step bound ``hmax`` (:func:`~flexbeam.kernels.pack_controls`)."""
        bits = _EVENT_MASKS.get(phase.events)
        if bits is None:
            bits = _EVENT_MASKS[phase.events] = sum(_EVENT_BITS[e] for e in phase.events)
        return pack_controls(rtol=self.rtol, atol=self.atol, max_step=hmax, omega_rigid=self.omega_rigid,
                             event_bits=bits, contacts=phase.buffer)  # fmt: skip

    def _run(
        self, ctrl: np.ndarray, state: np.ndarray, t_end: float, info: np.ndarray, chunks: list, handed: _Handed
    ) -> int:
        """The kernel's step loop from ``state`` to ``t_end`` or an event (``fb_advance``) in blocks of at most
        BLOCK_RECORDS step records, appended to ``chunks``; a stepper that hands on passes each BLOCK_RECORDS of
        them on (:meth:`_hand_on`). Returns the kernel's code."""
        capacity = 64
        while True:
            records = np.empty((capacity, self.record_size))
            if handed.coef is None:
                code, nrec, _ = core.advance(self.kernel, self.basis_buffer, ctrl, state, float(t_end), records, info)
            else:
                rows = np.empty((_SWITCH_ROWS, _SWITCH_HEAD + 4 * self.basis.N + _SWITCH_JUMP + 2))
                code, nrec, nsw = core.advance(self.kernel, self.basis_buffer, ctrl, state, float(t_end), records, info,
                                               handed.coef, rows)  # fmt: skip
                handed.switched += [(handed.total + int(r[0]), r) for r in rows[:nsw]]
            handed.total += nrec
            if nrec:
                chunks.append(records[:nrec])
                handed.held += nrec
            if code != _ADV_FULL:
                return code
            if self.hand_on is not None and handed.held >= BLOCK_RECORDS:  # the kernel resumes from `state`
                self._hand_on(state, chunks, handed)
            if self.stop is not None and self.stop():  # (a step's end: the state the kernel would resume from)
                return _ADV_STOPPED
            capacity = min(2 * capacity, BLOCK_RECORDS)

    def _hand_on(self, state: np.ndarray, chunks: list, handed: _Handed) -> None:
        """Pass the held records of a long phase on as one part (from where the last part ended, or the phase's
        start, to the state now), and drop them."""
        N = self.basis.N
        t_b = float(state[0])
        y_b = self.from_modal(state[5 : 5 + N], state[5 + N : 5 + 2 * N], state[2], state[3])
        t_a, y_a = handed.start if handed.start is not None else (handed.t, handed.y)
        part = ModalDense(self, np.ascontiguousarray(np.concatenate(chunks)))
        chunks.clear()
        handed.held = 0
        self.hand_on(t_a, y_a, t_b, y_b, part, handed.start is None)
        handed.start = (t_b, y_b)


@dataclass
class _Handed:
    """A phase's parts passed on so far: its start (t, y), the records held since the last part, and where that
    part ended (None before the first)."""

    t: float
    y: np.ndarray
    held: int = 0
    start: tuple[float, np.ndarray] | None = None
    #: the kernel's friction switches: its coef (None: not taken in the kernel), the records of the phase so far,
    #: and the switches taken since they were last collected (the index of the first record after each, its row)
    coef: np.ndarray | None = None
    total: int = 0
    switched: list = field(default_factory=list)
