"""The apparent coefficients of restitution of a free beam's collision episode (docs/free-beam.md, *Collision
episodes*), in the three definitions of W. J. Stronge, *Impact Mechanics* (Cambridge University Press, 2000),
chapter 2 (sec. 2.3-2.4) and chapter 4 (sec. 4.2, planar impact of a rigid body), applied to the beam's *rigid-body*
motion -- what an observer who sees the bar as a rigid body measures, as Stoianovici & Hurmuzlu (1996) did:

* the rigid-body motion is G's velocity v_G and the spin Omega = p_theta / J_G (the beam's angular momentum about
  G over its rigid rotary inertia: theta' for a rigid bar; conserved in free flight, so read anywhere in it);
* the striking point P is the first record's contact point; n its contact normal and a = (rho_P x n)_z its lever
  arm, both frozen at the episode's onset (the impact configuration, as in Stronge's rigid-body theory);
* P's normal velocity in that motion, the contact forces' share alone (gravity's impulse over the episode taken
  out; it is not impulsive): v(t) = n . (v_G(t) + g e_Y (t - t_0)) + a Omega(t).  It changes only through the
  contact impulse, dv = (1/m + a^2 / J_G) dp for the striking pair alone, so it rises monotonically through the
  episode;
* **compression** lasts from the onset t_0 until v first reaches zero (t_c), **restitution** from t_c to the
  episode's end t_1.  The rigid motion defines it, not the point's own velocity delta' (which the vibration makes
  cross zero at every micro-impact), because the apparent coefficients describe the rigid-body motion; with no
  modes the two coincide;
* Newton's e_N = -v(t_1) / v(t_0); Poisson's e_P = P_r / P_c, the normal impulses of restitution and compression;
  Stronge's energetic e_* = sqrt(-W_r / W_c), W = int F v dt the work of the normal force on the rigid-body motion
  in each phase (W_c < 0).  The impulses and works are integrated over the dense output with 8-point
  Gauss-Legendre per integrator step (the phases' ends and t_c as breaks); an IMM jump of impulse J is an
  impulse along which v rises linearly from v- to v+, so it adds J (v- + v+) / 2 of work, split at v = 0 when
  compression ends inside it.  The restitution impulse is the records' impulse (their nodal quadrature, exact for
  the collocated force: m dv_G to round-off) less the compression impulse.

For a rigid body at one frictionless contact v is linear in the impulse, and the three coincide (Stronge 2000,
sec. 4.2): an IMM impact of restitution e gives e_N = e_P = e_* = e to round-off.  A flexible beam's bending
vibration takes energy from the rigid motion and gives some back at later micro-impacts, and the three differ.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import numerics as nm

if TYPE_CHECKING:
    from ..integrate.loop import Segment
    from .arrays import RunSource
    from .records import ContactEvent

#: bisection for t_c stops at this bracket [s]
TC_XTOL = 1e-13
#: beta_1 L of the first free-free bending mode, the first root of cos z cosh z = 1
FREE_FREE_ROOT = 4.730040744862704


def free_free_period(length: float, bending_stiffness: float, line_density: float) -> float:
    """T_1 = 2 pi / ((beta_1 L)^2 sqrt(EI / (mu L^4))) [s], the first free-free bending period of a beam of
    ``length`` L, EI and mu (the continuum's)."""
    L = length
    return 2.0 * math.pi / (FREE_FREE_ROOT**2 * math.sqrt(bending_stiffness / (line_density * L**4)))


class Motion:
    """What the apparent restitution and the episodes read of a free beam's rigid-body motion (v_G, Omega): a run's
    dense output (:class:`RigidMotion`) or the finite-element reference's samples (``flexbeam.fem``)."""

    #: the beam's length L [m] and the first free-free bending period T_1 [s] (the default episode gap)
    length: float
    period: float
    #: the end of the run [s]
    t_final: float

    def state(self, t: float, after: bool) -> np.ndarray:
        """(v_Gx, v_Gy, Omega) at time t (``after``: after a jump there)."""
        raise NotImplementedError

    def strike(self, t0: float, pair: int) -> None:
        """Freeze the normal and lever arm of ``pair``'s contact point at the onset t0 (before any jump)."""
        raise NotImplementedError

    def at(self, t: float, after: bool) -> float:
        """v(t), the striking point's normal velocity in the rigid-body motion (:meth:`strike`), gravity's share
        taken out."""
        raise NotImplementedError

    def pieces(self, t0: float, t1: float, pair: int) -> Iterator[tuple[Piece, float, float]]:
        """The pieces of ``pair``'s contact force over [t0, t1]: (piece, lo, hi), one per stretch of dense output."""
        raise NotImplementedError

    def contact_position(self, t: float, pair: int) -> float:
        """Material coordinate of ``pair``'s contact point at time t (after a jump there) [m]."""
        raise NotImplementedError


class Piece:
    """One stretch of dense output in a contact: its integrator steps' breaks, the force and v on it."""

    def breaks(self) -> np.ndarray:
        raise NotImplementedError

    def force(self, times: np.ndarray) -> np.ndarray:
        """The striking pair's normal contact force [N]."""
        raise NotImplementedError

    def speed(self, times: np.ndarray) -> np.ndarray:
        """v(t) of the motion's frozen striking point."""
        raise NotImplementedError


class RigidMotion(Motion):
    """The rigid-body motion (v_G, Omega) of a free beam's run on its dense output."""

    def __init__(self, source: RunSource) -> None:
        self.source = source
        system = source.system
        self.n, self.nz = system.n, system.nz
        self.JG, self.Mc, self.g = system.beam.Jc, system.beam.Mc, system.g
        self.beam = system.beam
        self.normal, self.lever, self.t0 = np.array([0.0, 1.0]), 0.0, 0.0
        self.length = system.beam.length
        self.t_final = source.run.t_final

    @property
    def period(self) -> float:
        beam = self.source.system.beam
        return free_free_period(beam.length, beam.bending_stiffness, beam.line_density)

    def segment(self, t: float, after: bool) -> Segment:
        """The last segment holding t (``after``: after a jump there) or the first."""
        src = self.source
        segs = [s for s in (src.segments[i] for i in src._around(t, t)) if s.t0 <= t <= s.t1]
        return segs[-1] if after else segs[0]

    def rigid(self, Y: np.ndarray) -> np.ndarray:
        """(v_Gx, v_Gy, Omega) of states Y (rows)."""
        Y = np.atleast_2d(Y)
        nz = self.nz
        q = Y[:, 3:nz]
        if self.beam.axial is not None:
            return np.column_stack((Y[:, nz], Y[:, nz + 1], self._axial_spin(Y)))
        pq = np.einsum("ij,jk,ik->i", q, self.Mc, q) if self.n else np.zeros(Y.shape[0])
        return np.column_stack((Y[:, nz], Y[:, nz + 1], Y[:, nz + 2] * (1.0 + pq / self.JG)))

    def _axial_spin(self, Y: np.ndarray) -> np.ndarray:
        """p_theta / J_G with axial modes: theta' (J_G + q^T Mc q + 2 m_ta p + p^T M_aa p) + p^T S q' - q^T S^T p'."""
        nz, nb, ax = self.nz, self.beam.n, self.beam.axial
        q, p = Y[:, 3 : 3 + nb], Y[:, 3 + nb : nz]
        qd, pd = Y[:, nz + 3 : nz + 3 + nb], Y[:, nz + 3 + nb : 2 * nz]
        J = self.JG + np.einsum("ij,jk,ik->i", q, self.Mc, q) + p @ (2.0 * ax.mta) + (p * p) @ ax.Maa
        h = np.einsum("ik,kj,ij->i", p, ax.S, qd) - np.einsum("ik,kj,ij->i", pd, ax.S, q)
        return (Y[:, nz + 2] * J + h) / self.JG

    def state(self, t: float, after: bool) -> np.ndarray:
        """(v_Gx, v_Gy, Omega) at time t."""
        seg = self.segment(t, after)
        return self.rigid(seg.states(np.array([t])))[0]

    def strike(self, t0: float, pair: int) -> None:
        """Freeze the normal and lever arm of ``pair``'s contact point at the onset t0 (before any jump)."""
        y = self.segment(t0, after=False).states(np.array([t0]))[0]
        J = self.source.system.gap(t0, y, pair)[3]
        self.normal, self.lever, self.t0 = np.array(J[:2], float), float(J[2]), t0

    def velocity(self, times: np.ndarray, Y: np.ndarray) -> np.ndarray:
        """v(t): the striking point's normal velocity in the rigid-body motion, gravity's share taken out."""
        r = self.rigid(Y)
        vy = r[:, 1] + self.g * (np.asarray(times, float) - self.t0)
        return self.normal[0] * r[:, 0] + self.normal[1] * vy + self.lever * r[:, 2]

    def at(self, t: float, after: bool) -> float:
        seg = self.segment(t, after)
        return float(self.velocity(np.array([t]), seg.states(np.array([t])))[0])

    def pieces(self, t0: float, t1: float, pair: int) -> Iterator[tuple[Piece, float, float]]:
        for seg in self.source._contact_segments(t0, t1, pair):
            yield SegmentPiece(self, seg, pair), max(t0, seg.t0), min(t1, seg.t1)

    def contact_position(self, t: float, pair: int) -> float:
        seg = self.segment(t, after=True)
        return float(self.source.evaluate_pairs(seg, np.array([t]))[2][0, pair, 3])


class SegmentPiece(Piece):
    """A segment of a run's dense output."""

    def __init__(self, motion: RigidMotion, seg: Segment, pair: int) -> None:
        self.motion, self.seg, self.pair = motion, seg, pair

    def breaks(self) -> np.ndarray:
        return self.seg.breaks()

    def force(self, times: np.ndarray) -> np.ndarray:
        return self.motion.source.pair_force(self.seg, times, self.pair)

    def speed(self, times: np.ndarray) -> np.ndarray:
        return self.motion.velocity(times, self.seg.states(times))


class Phases:
    """Impulse and work of the normal force in compression and restitution, accumulated piece by piece."""

    def __init__(self, compressing: bool, t0: float) -> None:
        self.compressing = compressing
        self.tc = math.nan if compressing else t0
        self.P = [0.0, 0.0]  # compression, restitution
        self.W = [0.0, 0.0]

    def add(self, phase: int, impulse: float, work: float) -> None:
        self.P[phase] += impulse
        self.W[phase] += work

    def jump(self, t: float, J: float, vm: float, vp: float) -> None:
        """An impulse J along which v rises linearly from vm to vp."""
        if self.compressing and vp >= 0.0:
            pc = J * (-vm) / (vp - vm)
            self.add(0, pc, 0.5 * pc * vm)
            self.add(1, J - pc, 0.5 * (J - pc) * vp)
            self.compressing, self.tc = False, t
        else:
            self.add(0 if self.compressing else 1, J, 0.5 * J * (vm + vp))

    def steps(self, piece: Piece, lo: float, hi: float) -> None:
        """The contact force on ``piece`` over [lo, hi]."""
        b = np.unique(np.clip(piece.breaks(), lo, hi))
        if b.size < 2:
            return
        if self.compressing:
            v = piece.speed(b)
            up = np.nonzero(v >= 0.0)[0]
            if up.size:
                i = int(up[0])
                tc = float(b[0]) if i == 0 else _bisect(piece, float(b[i - 1]), float(b[i]))
                self.add(0, *_quad(piece, b[b <= tc], tc))
                self.compressing, self.tc = False, tc
                self.add(1, *_quad(piece, np.concatenate(([tc], b[b > tc])), None))
                return
        self.add(0 if self.compressing else 1, *_quad(piece, b, None))


def _quad(piece: Piece, b: np.ndarray, end: float | None) -> tuple[float, float]:
    """(int F dt, int F v dt) over the steps between the breaks b (and ``end`` appended)."""
    if end is not None:
        b = np.concatenate((b, [end]))
    b = np.unique(b)
    a, c = b[:-1], b[1:]
    keep = c > a
    a, c = a[keep], c[keep]
    if not a.size:
        return 0.0, 0.0
    x, w = nm.leggauss(8)
    t = (0.5 * (c - a)[:, None] * (x[None, :] + 1.0) + a[:, None]).ravel()
    F = piece.force(t)
    v = piece.speed(t)
    h = np.repeat(0.5 * (c - a), x.size) * np.tile(w, a.size)
    return nm.fsum(h * F), nm.fsum(h * F * v)


def _bisect(piece: Piece, lo: float, hi: float) -> float:
    """The time in [lo, hi] where v crosses zero (v(lo) < 0 <= v(hi)), to :data:`TC_XTOL`."""
    for _ in range(200):
        if hi - lo <= TC_XTOL:
            break
        mid = 0.5 * (lo + hi)
        if piece.speed(np.array([mid]))[0] >= 0.0:
            hi = mid
        else:
            lo = mid
    return hi


def apparent_restitution(
    motion: Motion, records: list[ContactEvent], pair: int, t0: float, t1: float, one_point: bool = True
) -> dict[str, Any]:
    """The episode's rigid-body normal velocities, compression end, impulses, works and apparent coefficients
    (the module docstring) for the records of one episode from ``t0`` to ``t1``; the coefficients are NaN unless
    ``one_point`` (every record strikes at the first one's point)."""
    motion.strike(t0, pair)
    v_before, v_after = motion.at(t0, after=False), motion.at(t1, after=True)
    acc = Phases(v_before < 0.0, t0)
    for ev in records:
        if ev.pair != pair:
            continue
        if not math.isnan(ev.jump_impulse):
            acc.jump(ev.onset, ev.jump_impulse, motion.at(ev.onset, after=False), motion.at(ev.onset, after=True))
        end = ev.end if math.isfinite(ev.end) else motion.t_final
        if end > ev.onset:
            for piece, lo, hi in motion.pieces(ev.onset, end, pair):
                acc.steps(piece, lo, hi)
    return restitution_record(acc, records, pair, v_before, v_after, one_point)


def restitution_record(
    acc: Phases, records: list[ContactEvent], pair: int, v_before: float, v_after: float, one_point: bool
) -> dict[str, Any]:
    """What :func:`apparent_restitution` gives from the impulses and works accumulated over an episode (``acc``),
    its records (their impulses completed) and the rigid-body normal velocities before and after."""
    (Pc, _), (Wc, Wr) = acc.P, acc.W
    Pr = math.fsum(ev.impulse for ev in records if ev.pair == pair) - Pc  # the records' impulses: exact quadrature
    ok = one_point and v_before < 0.0
    return {
        "normal_velocity_before": v_before,
        "normal_velocity_after": v_after,
        "compression_end": acc.tc,
        "compression_impulse": Pc,
        "restitution_impulse": Pr,
        "compression_work": Wc,
        "restitution_work": Wr,
        "restitution_newton": -v_after / v_before if ok else math.nan,
        "restitution_poisson": Pr / Pc if ok and Pc > 0.0 else math.nan,
        "restitution_energetic": math.sqrt(-Wr / Wc) if ok and Wc < 0.0 and Wr >= 0.0 else math.nan,
    }
