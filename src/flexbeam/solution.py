"""The result of a simulation: arrays, contact-event log, status, statistics, provenance.

:class:`Solution` is what every impact method returns.  Its :meth:`Solution.metrics`
are the numbers the CLI's ``--json`` prints (the names are a contract), and
:meth:`Solution.to_xarray` gives an :class:`xarray.Dataset` with ``units`` and
``long_name`` on every variable.
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .contact_counts import ContactCounts, classify_contacts
from .metrics import METRICS

if TYPE_CHECKING:
    from .sampling import RunSource

#: variable name -> (units, long name)
VARIABLES: dict[str, tuple[str, str]] = {
    "theta": ("rad", "Hub angle"),
    "theta_rate": ("rad/s", "Hub angular velocity"),
    "q": ("1", "Modal coordinate"),
    "q_rate": ("1/s", "Modal velocity"),
    "contact_force": ("N", "Contact force"),
    "gap": ("m", "Gap at the contact point"),
    "normal_velocity": ("m/s", "Normal velocity of the contact point"),
    "measuring_velocity": ("m/s", "Normal velocity of the measuring points"),
    "kinetic_energy": ("J", "Kinetic energy"),
    "elastic_energy": ("J", "Elastic energy"),
    "gravitational_energy": ("J", "Gravitational energy"),
    "contact_energy": ("J", "Contact potential energy"),
    "dissipated_energy": ("J", "Energy dissipated by contact (and the support's dashpot)"),
    "drive_work": ("J", "Work of the joint torque"),
    "total_energy": ("J", "Total energy including dissipated and drive work"),
    "joint_torque": ("N m", "Joint torque"),
    "tip_deflection": ("m", "Tip deflection in the rotating frame"),
    "support_displacement": ("m", "Displacement s of the compliant obstacle along its support axis"),
    "sensor_force": ("N", "Force read under the compliant obstacle support, -(k_s s + c_s s')"),
    "pair_gap": ("m", "Gap of each contact pair"),
    "pair_normal_velocity": ("m/s", "Normal velocity of each contact pair's point"),
    "pair_contact_force": ("N", "Contact force of each contact pair"),
    "pair_contact_position": ("m", "Material coordinate x of each contact pair's point (moves for contact anywhere)"),
}
#: variables (time x pair) present only when a case has several contact pairs or a contact anywhere
PAIR_VARIABLES = ("pair_gap", "pair_normal_velocity", "pair_contact_force", "pair_contact_position")


@dataclass
class ContactEvent:
    """One contact (or, for IMM, one instantaneous impact).

    Times in s; velocities are P's normal velocity delta' [m/s] (negative = approaching) just before the
    contact and at its end (IMM: right after the jump).  ``impulse`` [N s] is the whole contact's: the jump at
    onset (IMM, CCM's e = 0 step; also in ``jump_impulse``) plus the integral of the contact force until
    ``end`` (CCFM's force, CCM's multiplier, a resting contact's reaction).  ``energy_before``/``energy_after``
    [J] are the mechanical energy T + V_e + V_g just before the onset (before its jump) and at the end.
    ``pair``: the contact pair (0: ``[contact]`` against ``[obstacle]``, k: ``obstacles[k - 1]``);
    ``time_scale``: the contact's expected duration at onset (a rigid-body Hertz impact; CCFM) [s].
    """

    index: int
    onset: float
    end: float = float("nan")
    velocity_before: float = float("nan")
    velocity_after: float = float("nan")
    impulse: float = float("nan")
    peak_force: float = float("nan")
    peak_time: float = float("nan")
    energy_before: float = float("nan")
    energy_after: float = float("nan")
    jump_impulse: float = float("nan")
    pair: int = 0
    time_scale: float = float("nan")

    @property
    def duration(self) -> float:
        return self.end - self.onset


#: peak refinement stops at this bracket [s]: near a peak F ~ F_max (1 - ((t - t_p) / tau)^2) with
#: tau >~ 1e-5 s for any contact pulse resolved at all, so the force is then exact to ~1e-10 relative
PEAK_XTOL = 1e-10


def interior_maxima(f: np.ndarray, rtol: float = 1e-9, start: bool = False) -> list[int]:
    """Indices of the sampled local maxima of f (a plateau counts once, at its start).

    A maximum must stand above its lower neighbour by more than ``rtol`` max|f|: the
    round-off ripple of a constant force (a contact resting under a static load) is no peak.
    ``start``: the first sample counts too when it stands above the second by that much.
    """
    tol = rtol * float(np.max(np.abs(f), initial=0.0))
    mid, left, right = f[1:-1], f[:-2], f[2:]
    idx = (np.nonzero((mid > left) & (mid >= right) & (mid - np.minimum(left, right) > tol))[0] + 1).tolist()
    if start and f.size > 1 and f[0] - f[1] > tol:
        idx.insert(0, 0)
    return idx


def zoom_max(f, a: float, b: float, xtol: float, points: int = 33) -> tuple[float, float]:
    """Maximum of f on [a, b] by repeated zooming on a grid: f (vectorised, times -> values) at ``points``
    points, then the grid around the largest value, until the bracket is below ``xtol``.

    For a force near a smooth peak this needs log(xtol / (b - a)) / log(points / 2) calls of f (4 from a step of
    1e-5 s to 1e-10 s), each a single vectorised evaluation.
    """
    best_t, best_f = a, -math.inf
    while True:
        t = np.linspace(a, b, points)
        v = np.asarray(f(t), float)
        i = int(np.argmax(v))
        if v[i] > best_f:
            best_t, best_f = float(t[i]), float(v[i])
        if b - a <= xtol:
            return best_t, best_f
        dt = (b - a) / (points - 1)
        a, b = max(a, t[i] - dt), min(b, t[i] + dt)


def golden_max(f, a: float, b: float, xtol: float) -> tuple[float, float]:
    """Maximum of a unimodal f on [a, b] by golden-section search (Kiefer 1953).

    Plain Python on purpose: the peak refinement then does not import scipy.optimize,
    which would cost the command line ~0.5 s of start-up.
    """
    r = (math.sqrt(5.0) - 1.0) / 2.0
    c, d = b - r * (b - a), a + r * (b - a)
    fc, fd = float(f(c)), float(f(d))
    while b - a > xtol:
        if fc >= fd:
            b, d, fd = d, c, fc
            c = b - r * (b - a)
            fc = float(f(c))
        else:
            a, c, fc = c, d, fd
            d = a + r * (b - a)
            fd = float(f(d))
    return (c, fc) if fc >= fd else (d, fd)


class Solution:
    """Arrays over the output samples plus the contact log and run information.

    Attributes
    ----------
    time
        Sample times [s] (event instants included; a velocity jump gives two samples at the same time).
    phase
        Phase name of each sample ("free", "contact", "constrained", "resting").
    arrays
        Name -> array, see :data:`VARIABLES`.
    contacts
        Contact-event log.
    status, message
        "success", "failed", "max-contacts", ... and the reason.
    stats
        steps, nfev, wall_time [s] (integration alone).
    provenance
        Version, case (TOML), method, tolerances, derived parameters.

    The arrays are given (the finite-element reference) or evaluated on first use from the run's dense output
    (``source``, a :class:`~flexbeam.sampling.RunSource`): the metrics do not need them.  With given arrays,
    ``force_at(t, pair)`` -- a contact pair's force F_k(t) [N] on a dense output, 0 outside its contact phases --
    refines each contact's force peaks between the samples (the samples' maximum without it); with a ``source``
    its own :meth:`~flexbeam.sampling.RunSource.force_at` is used.
    """

    def __init__(
        self,
        time: np.ndarray | None = None,
        phase: np.ndarray | None = None,
        arrays: dict[str, np.ndarray] | None = None,
        contacts: list[ContactEvent] | None = None,
        status: str = "success",
        message: str = "",
        stats: dict[str, float] | None = None,
        provenance: dict[str, Any] | None = None,
        measuring_points: np.ndarray | None = None,
        force_at: Callable[[float, int], float] | None = None,
        source: RunSource | None = None,
    ) -> None:
        if source is None and (time is None or phase is None or arrays is None):
            raise ValueError("Solution: give time, phase and arrays, or a source")
        self._samples = None if source is not None else (np.asarray(time), np.asarray(phase), arrays)
        self._contacts = list(contacts or [])
        self._completed: set[int] = set()
        self.status, self.message = status, message
        self.stats = dict(stats or {})
        self._provenance = dict(provenance or {})
        self.measuring_points = np.empty(0) if measuring_points is None else np.asarray(measuring_points, float)
        self._force_at = force_at if source is None else source.force_at
        self.source = source
        self._peaks: dict[int, list[tuple[float, float]]] = {}

    # ----------------------------------------------------------------- samples
    def _loaded(self) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
        if self._samples is None:
            assert self.source is not None
            self._samples = self.source.samples
        return self._samples

    @property
    def time(self) -> np.ndarray:
        return self._loaded()[0]

    @property
    def phase(self) -> np.ndarray:
        return self._loaded()[1]

    @property
    def arrays(self) -> dict[str, np.ndarray]:
        return self._loaded()[2]

    @property
    def provenance(self) -> dict[str, Any]:
        """Version, case (TOML), method, tolerances, derived parameters (a callable entry is evaluated when the
        provenance is first read: the case's TOML text is written only for an export)."""
        for key, value in self._provenance.items():
            if callable(value):
                self._provenance[key] = value()
        return self._provenance

    @property
    def contacts(self) -> list[ContactEvent]:
        """The contact log, each record completed (impulse, energies, peak) on first use."""
        for i in range(len(self._contacts)):
            self.contact(i)
        return self._contacts

    def contact(self, i: int) -> ContactEvent:
        """Contact record ``i``; a run's impulse, energies before/after and peak are found on its dense output
        the first time it is asked for (a jump's impulse and energies are logged at the jump)."""
        ev = self._contacts[i]
        if i in self._completed or self.source is None:
            return ev
        self._completed.add(i)
        src = self.source
        end = ev.end if math.isfinite(ev.end) else src.run.t_final
        jumped = not math.isnan(ev.jump_impulse)
        if jumped:  # the jump logged kinetic energies: add the potential, which a jump leaves unchanged
            potential = src.mechanical_energy(ev.onset, after=True) - ev.energy_after
            ev.energy_before += potential
            ev.energy_after += potential
        if end > ev.onset:
            ev.impulse = (ev.jump_impulse if jumped else 0.0) + src.impulse(ev.onset, end, ev.pair)
            if not jumped:
                ev.energy_before = src.mechanical_energy(ev.onset, after=True)
            ev.energy_after = src.mechanical_energy(end)
        peaks = self.force_peaks(i, threshold=0.0)
        if peaks:
            ev.peak_time, ev.peak_force = max(peaks, key=lambda p: p[1])
        return ev

    @cached_property
    def _in_contact(self) -> np.ndarray:
        """Samples of contact, constrained or resting phases (bool per sample)."""
        return np.isin(self.phase, ("contact", "constrained", "resting"))

    def __getitem__(self, name: str) -> np.ndarray:
        return self.arrays[name]

    @property
    def method(self) -> str:
        return str(self._provenance.get("method", ""))

    def _repr_html_(self) -> str:
        """Notebook display: status, metrics and a small plot (:func:`flexbeam.display.solution_html`)."""
        from .display import solution_html

        return solution_html(self)

    # ----------------------------------------------------------------- metrics
    def energy_drift(self) -> tuple[float, float]:
        """(end, max) relative change of the total energy.

        Relative to ``max(|E(0)|, max_t T(t))`` so that a zero gravitational reference does not divide by
        zero.  With a run's dense output the energies are those at every step boundary, else at the samples.
        """
        if self.source is not None:
            _, E, T = self.source.checkpoints
        else:
            E, T = self.arrays["total_energy"], self.arrays["kinetic_energy"]
        if E.size == 0:
            return math.nan, math.nan
        scale = max(abs(E[0]), float(np.max(T)), 1e-300)
        return float((E[-1] - E[0]) / scale), float(np.max(np.abs(E - E[0])) / scale)

    def _refine_max(self, t_guess: float, h: float, lo: float, hi: float, pair: int = 0) -> tuple[float, float]:
        if self.source is not None:
            a, b = max(lo, t_guess - h), min(hi, t_guess + h)
            force = lambda t: self.source.force_many(t, pair)  # noqa: E731
            if b <= a:
                return t_guess, float(force(np.array([t_guess]))[0])
            return zoom_max(force, a, b, xtol=PEAK_XTOL)
        if self._force_at is None:
            i = int(np.argmin(np.abs(self.time - t_guess)))
            return float(self.time[i]), float(self.arrays["contact_force"][i])
        force = lambda t: self._force_at(t, pair)  # noqa: E731
        a, b = max(lo, t_guess - h), min(hi, t_guess + h)
        if b <= a:
            return t_guess, float(force(t_guess))
        t_max, f_max = golden_max(force, a, b, xtol=PEAK_XTOL)
        f_guess = float(force(t_guess))
        if f_max >= f_guess:
            return t_max, f_max
        return t_guess, f_guess

    def _force_samples(self, ev: ContactEvent) -> tuple[np.ndarray, np.ndarray]:
        """(times, force) of one contact: on the dense output (a run) or at the samples."""
        end = ev.end if math.isfinite(ev.end) else math.inf
        if self.source is not None:
            t1 = end if math.isfinite(end) else self.source.run.t_final
            return self.source.force_profile(ev.onset, t1, ev.pair)
        t = self.time
        sel = np.nonzero((t >= ev.onset) & (t <= end) & self._in_contact)[0]
        if "pair_contact_force" in self.arrays:
            return t[sel], self.arrays["pair_contact_force"][sel, ev.pair]
        return t[sel], self.arrays["contact_force"][sel]

    def force_peaks(self, contact: int = 0, threshold: float = 0.05) -> list[tuple[float, float]]:
        """Local maxima (time [s], force [N]) of one contact's force above ``threshold`` x peak."""
        if contact >= len(self._contacts):
            return []
        if contact not in self._peaks:
            self._peaks[contact] = self._all_peaks(contact)
        peaks = self._peaks[contact]
        if not peaks:
            return []
        top = max(p[1] for p in peaks)
        return [p for p in peaks if p[1] > threshold * top]

    def _all_peaks(self, contact: int) -> list[tuple[float, float]]:
        ev = self._contacts[contact]
        tt, f = self._force_samples(ev)
        if tt.size < 3:
            return []
        end = ev.end if math.isfinite(ev.end) else float(tt[-1])
        h = float(np.median(np.diff(tt))) if tt.size > 1 else 0.0
        idx = interior_maxima(f, start=True)
        return [self._refine_max(float(tt[i]), h, ev.onset, end, ev.pair) for i in idx]

    def sensor_pulse(self, threshold: float = 0.05) -> tuple[list[tuple[float, float]], float]:
        """Peaks (time [s], force [N]) and duration [s] of the first sensor-force pulse.

        Compliant support only.  Like the experiment, which "determined the beginning and ending of the impact
        by the sign of the impact force" (Duan et al. 2013, Sec. 4), the pulse runs from the first contact's
        onset until the sensor force -(k_s s + c_s s') first returns to zero (linear interpolation between
        samples); its peaks are the sampled local maxima above ``threshold`` x its maximum.
        """
        if "sensor_force" not in self.arrays or not self._contacts:
            return [], math.nan
        onset = self._contacts[0].onset
        t, f = self.time, self.arrays["sensor_force"]
        i0 = int(np.searchsorted(t, onset))
        pos = np.nonzero(f[i0:] > 0.0)[0]
        if pos.size == 0:
            return [], math.nan
        first = i0 + int(pos[0])
        back = np.nonzero(f[first:] <= 0.0)[0]
        if back.size:
            k = first + int(back[0])
            end = float(t[k - 1] + (t[k] - t[k - 1]) * f[k - 1] / (f[k - 1] - f[k]))
        else:
            k, end = t.size, math.nan
        ff, tt = f[i0:k], t[i0:k]
        peaks = [(float(tt[i]), float(ff[i])) for i in interior_maxima(ff)]
        if not peaks:
            return [], end - onset
        top = max(p[1] for p in peaks)
        return [p for p in peaks if p[1] > threshold * top], end - onset

    def _contact_metrics(self, i: int | None) -> dict[str, Any]:
        """The per-contact metrics of contact ``i`` (impact and post-impact velocity, duration, impulse, energies,
        peak force and its time, local force maxima, second peak); ``None``: the same keys, NaN and empty lists
        (a pair that never touched)."""
        out: dict[str, Any] = {
            "impact_velocity": math.nan,
            "post_impact_velocity": math.nan,
            "contact_duration": math.nan,
            "impulse": math.nan,
            "energy_before": math.nan,
            "energy_after": math.nan,
            "peak_force": math.nan,
            "peak_time": math.nan,
            "force_peaks": [],
            "force_peak_times": [],
            "second_peak_force": math.nan,
        }
        if i is None:
            return out
        ev = self.contact(i)
        out.update(
            impact_velocity=ev.velocity_before,
            post_impact_velocity=ev.velocity_after,
            contact_duration=ev.duration,
            impulse=ev.impulse,
            energy_before=ev.energy_before,
            energy_after=ev.energy_after,
        )
        peaks = self.force_peaks(i)
        if peaks:
            tp, fp = max(peaks, key=lambda p: p[1])
            others = [p[1] for p in peaks if p[0] != tp]
            out.update(
                peak_force=fp,
                peak_time=tp - ev.onset,
                force_peaks=[p[1] for p in peaks],
                force_peak_times=[p[0] - ev.onset for p in peaks],
                second_peak_force=max(others) if others else math.nan,
            )
        return out

    @property
    def pair_labels(self) -> list[str]:
        """The obstacle of each contact pair (pair 0: ``"obstacle"``, the case's ``[obstacle]``)."""
        return list(self._provenance.get("contact_pairs") or ["obstacle"])

    def contact_counts(self) -> ContactCounts:
        """The contact records sorted into contacts and micro-impacts, the micro-impacts grouped into chatter
        episodes: :func:`flexbeam.contact_counts.classify_contacts` on every record's impulse and approach speed
        (docs/methods.md, *What one contact is*)."""
        c = self.contacts
        return classify_contacts(
            [ev.pair for ev in c], [ev.impulse for ev in c], [-ev.velocity_before for ev in c], len(self.pair_labels)
        )

    def events(self, counts: ContactCounts | None = None) -> list[dict[str, Any]]:
        """One dict per contact record, in the order of their onsets (the ``events`` of :meth:`metrics`).

        ``index`` (the record's place in :attr:`contacts`), ``pair``, ``obstacle``, ``onset``, ``end`` [s],
        ``duration`` [s], ``peak_force`` [N] and ``peak_time`` [s after the onset] (NaN without a force
        history: an IMM impact), ``velocity_before``, ``velocity_after`` [m/s] (P's normal velocity, negative
        approaching), ``impulse`` [N s], ``kind`` (``"contact"`` or ``"micro-impact"``) and ``chatter_episode``
        (the micro-impact's episode, None for a contact); ``counts``: :meth:`contact_counts`, if already known.
        """
        counts = self.contact_counts() if counts is None else counts
        labels = self.pair_labels
        return [
            {
                "index": i,
                "pair": ev.pair,
                "obstacle": labels[ev.pair],
                "onset": ev.onset,
                "end": ev.end,
                "duration": ev.duration,
                "peak_force": ev.peak_force,
                "peak_time": ev.peak_time - ev.onset,
                "velocity_before": ev.velocity_before,
                "velocity_after": ev.velocity_after,
                "impulse": ev.impulse,
                "kind": counts.kind(i),
                "chatter_episode": counts.episode[i],
            }
            for i, ev in enumerate(self.contacts)
        ]

    def metrics(self) -> dict[str, Any]:
        """The run's summary numbers (the ``--json`` contract of ``flexbeam run``), in the order, units and
        meaning of the registry :data:`flexbeam.metrics.METRICS` (NaN or an empty list when not defined).

        ``peak_force`` [N], ``peak_time`` [s after the first onset], ``contact_duration`` [s], ``force_peaks``
        (list of local maxima [N] above 5 % of the peak) with ``force_peak_times`` [s after onset],
        ``contacts`` (the records that are not micro-impacts, :meth:`contact_counts`) with ``contact_records``,
        ``micro_impacts`` and ``chatter_episodes``, ``post_impact_velocity`` (P's normal velocity at the end of
        the first contact [m/s], positive away from the obstacle), ``energy_drift``, ``wall_time`` [s],
        ``steps``; the per-contact ones are those of the first contact record of pair 0 (``[contact]`` against
        ``[obstacle]``); ``pairs`` lists, for every pair, its counts and its first record's metrics (the same
        keys for every pair, NaN and empty lists for a pair that never touched); ``events`` lists every record
        (:meth:`events`); with a compliant obstacle support also ``sensor_peak_force``,
        ``sensor_second_peak_force`` [N] and ``sensor_duration`` [s] of the first sensor-force pulse
        (:meth:`sensor_pulse`).
        """
        drift, drift_max = self.energy_drift()
        out: dict[str, Any] = {
            name: ([] if m.kind in ("numbers", "records") else math.nan)
            for name, m in METRICS.items()
            if m.scope != "sensor"
        }
        counts = self.contact_counts()
        out.update(
            method=self.method,
            status=self.status,
            message=self.message,
            **counts.of_pair(None),
            energy_drift=drift,
            energy_drift_max=drift_max,
            wall_time=self.stats.get("wall_time", math.nan),
            steps=int(self.stats.get("steps", 0)),
            nfev=int(self.stats.get("nfev", 0)),
        )
        labels = self.pair_labels
        firsts = [next((i for i, ev in enumerate(self._contacts) if ev.pair == k), None) for k in range(len(labels))]
        if firsts[0] is not None:
            out.update(self._contact_metrics(firsts[0]))
        out["pairs"] = [
            {"pair": k, "obstacle": label, **counts.of_pair(k), **self._contact_metrics(i)}
            for k, (label, i) in enumerate(zip(labels, firsts))
        ]
        out["events"] = self.events(counts)
        if self._provenance.get("compliant_support") or (self._samples is not None and "sensor_force" in self.arrays):
            peaks, duration = self.sensor_pulse()
            ranked = sorted((p[1] for p in peaks), reverse=True)
            out["sensor_peak_force"] = ranked[0] if ranked else math.nan
            out["sensor_second_peak_force"] = ranked[1] if len(ranked) > 1 else math.nan
            out["sensor_duration"] = duration
        if self.source is not None:
            out["tip_deflection_min"], out["tip_deflection_max"] = self.source.extremes("tip_deflection")
        elif "tip_deflection" in self.arrays and self.arrays["tip_deflection"].size:
            out["tip_deflection_min"] = float(np.min(self.arrays["tip_deflection"]))
            out["tip_deflection_max"] = float(np.max(self.arrays["tip_deflection"]))
        return out

    def animate(self, path: str | Path, **options: Any) -> Path:
        """Render an animation of this run to ``path`` (.gif or .mp4): the deformed beam with magnified
        deflection, the hub, the obstacle and the contact force, in slow motion through the contacts.

        ``options`` as for :func:`flexbeam.animation.animate` (``scale``, ``window``, ``frames``, ``fps``,
        ``size``, ...); returns the path written.
        """
        from .animation import animate

        return animate(self, path, **options)

    # ------------------------------------------------------------------ export
    def to_xarray(self):
        """:class:`xarray.Dataset` with dims time, mode, point, contact; units in attrs."""
        import xarray as xr

        n_modes = self.arrays["q"].shape[1] if self.arrays["q"].ndim == 2 else 0
        data_vars: dict[str, Any] = {}
        for name, arr in self.arrays.items():
            units, long_name = VARIABLES[name]
            if name in ("q", "q_rate"):
                dims: tuple[str, ...] = ("time", "mode")
            elif name == "measuring_velocity":
                dims = ("time", "point")
            elif name.startswith("pair_"):
                dims = ("time", "pair")
            else:
                dims = ("time",)
            data_vars[name] = (dims, arr, {"units": units, "long_name": long_name})
        data_vars["phase"] = (("time",), self.phase.astype(str), {"long_name": "Phase of motion"})
        c = self.contacts
        counts = self.contact_counts()
        episodes = [math.nan if k is None else k for k in counts.episode]
        contact_fields = {
            "contact_onset": ("s", "Contact onset time", [e.onset for e in c]),
            "contact_end": ("s", "Contact end time", [e.end for e in c]),
            "contact_velocity_before": ("m/s", "Normal velocity of P before contact", [e.velocity_before for e in c]),
            "contact_velocity_after": ("m/s", "Normal velocity of P after contact", [e.velocity_after for e in c]),
            "contact_impulse": ("N s", "Contact impulse", [e.impulse for e in c]),
            "contact_peak_force": ("N", "Peak contact force", [e.peak_force for e in c]),
            "contact_pair": ("1", "Contact pair of the contact (0: [contact] against [obstacle])", [e.pair for e in c]),
            "contact_micro_impact": ("1", "1 for a micro-impact, 0 for a contact (docs/methods.md)", counts.micro),
            "contact_chatter_episode": ("1", "Chatter episode of a micro-impact (NaN for a contact)", episodes),
        }
        for name, (units, long_name, values) in contact_fields.items():
            data_vars[name] = (("contact",), np.asarray(values, float), {"units": units, "long_name": long_name})
        coords = {
            "time": ("time", self.time, {"units": "s", "long_name": "Time"}),
            "mode": ("mode", np.arange(1, n_modes + 1), {"long_name": "Mode number"}),
            "point": ("point", self.measuring_points, {"units": "m", "long_name": "Measuring point x"}),
            "contact": ("contact", np.arange(len(c)), {"long_name": "Contact index"}),
        }
        if any(name.startswith("pair_") for name in self.arrays):
            labels = self._provenance.get("contact_pairs") or []
            coords["pair"] = ("pair", np.asarray(labels, str), {"long_name": "Contact pair (its obstacle)"})
        attrs = {
            "title": "flexbeam simulation",
            "status": self.status,
            "message": self.message,
            "metrics": json.dumps(jsonable(self.metrics())),
            **{
                k: (v if isinstance(v, (str, int, float)) else json.dumps(jsonable(v)))
                for k, v in self.provenance.items()
            },
        }
        return xr.Dataset(data_vars, coords=coords, attrs=attrs)

    def to_netcdf(self, path: str | Path, time_chunk: int = 4096) -> Path:
        """Write the dataset to NetCDF-4 atomically (temporary file, then rename).

        Lossless compression: every non-empty variable is deflated (zlib level 4) after
        the byte shuffle, in chunks of ``time_chunk`` samples along ``time`` (whole along
        the other dimensions), so reading a time window decompresses only its chunks.
        ``phase`` is stored as a character array (variable-length strings cannot be
        compressed) and reads back as strings.  The seed experiment's result shrinks from
        11.3 MB to 7.2 MB: the float64 histories' low bits do not compress.
        """
        path = Path(path)
        ds = self.to_xarray()
        encoding: dict[str, dict[str, Any]] = {}
        for name, var in ds.variables.items():
            if var.size == 0 or var.dtype.kind not in "fiuU":
                continue
            chunks = [min(time_chunk, n) if dim == "time" else n for dim, n in zip(var.dims, var.shape)]
            enc: dict[str, Any] = {"zlib": True, "complevel": 4, "shuffle": True}
            if var.dtype.kind == "U":
                enc["dtype"] = "S1"
                chunks.append(max(1, var.dtype.itemsize // np.dtype("U1").itemsize))
            encoding[name] = {**enc, "chunksizes": tuple(chunks)}
        with atomic_path(path) as tmp:
            ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4", encoding=encoding)
        return path


class atomic_path:
    """Context manager giving a temporary path next to ``path``, renamed on success."""

    def __init__(self, path: Path) -> None:
        self.path = Path(path)

    def __enter__(self) -> Path:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fd, name = tempfile.mkstemp(prefix=f".{self.path.name}.", dir=self.path.parent)
        os.close(fd)
        self.tmp = Path(name)
        return self.tmp

    def __exit__(self, exc_type, exc, tb) -> None:
        if exc_type is None:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(self.tmp, 0o666 & ~umask)
            os.replace(self.tmp, self.path)
        else:
            self.tmp.unlink(missing_ok=True)


def write_text_atomic(path: str | Path, text: str) -> Path:
    """Write text to ``path`` atomically."""
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return path


def jsonable(obj: Any) -> Any:
    """``obj`` with numpy scalars as Python numbers and non-finite floats as None (strict JSON)."""
    if isinstance(obj, dict):
        return {k: jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else None
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def metrics_json(metrics: dict[str, Any]) -> str:
    """JSON text of metrics (NaN -> null)."""
    return json.dumps(jsonable(metrics), indent=2)
