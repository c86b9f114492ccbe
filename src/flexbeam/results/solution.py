"""The result of a simulation: arrays, contact-event log, status, statistics, provenance.

:class:`Solution` is what every impact method returns.  Its :meth:`Solution.metrics`
are the numbers the CLI's ``--json`` prints (the names are a contract), and
:meth:`Solution.to_xarray` gives an :class:`xarray.Dataset` with ``units`` and
``long_name`` on every variable.  Its views -- :meth:`Solution.plot`, :meth:`Solution.animate` and the notebook
display -- are those of :mod:`flexbeam.views`, reached through one accessor that the views register
(:mod:`flexbeam.views.accessor`, as xarray's ``DataArray.plot``): this layer does not import them.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from . import export, summary
from .arguments import nonnegative, positive_or_none, record_index
from .counts import ContactCounts
from .episodes import Episode, find_episodes, is_free
from .files import file_stamp
from .friction import tangential_impulse
from .peaks import PEAK_XTOL, golden_max, interior_maxima
from .records import ContactEvent

if TYPE_CHECKING:
    import xarray as xr

    from .arrays import RunSource
    from .restitution import Motion


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

    The arrays are given (the finite-element reference), evaluated on first use from the run's dense output
    (``source``, a :class:`~flexbeam.results.arrays.RunSource`): the metrics do not need them, or read on first use
    from the result ``file`` a streamed run wrote (:mod:`flexbeam.results.stream`; each variable when it is asked
    for), whose ``summaries`` -- ``energy_drift`` (end, max), ``tip_deflection`` (min, max), ``sensor_pulse`` (peaks,
    duration) -- the stream computed while the run went on.  With given arrays, ``force_at(t, pair)`` -- a contact
    pair's force F_k(t) [N] on a dense output, 0 outside its contact phases -- refines each contact's force peaks
    between the samples (the samples' maximum without it); with a ``source`` its own
    :meth:`~flexbeam.results.arrays.RunSource.force_at` is used.  ``motion``: a free beam's rigid-body motion
    (:class:`~flexbeam.results.restitution.Motion`) for its collision episodes, given with the arrays (the
    finite-element reference's; a run's is read from its ``source``).
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
        file: str | Path | None = None,
        summaries: dict[str, Any] | None = None,
        motion: Motion | None = None,
    ) -> None:
        if source is None and file is None and (time is None or phase is None or arrays is None):
            raise ValueError("Solution: give time, phase and arrays, a source or a file")
        self.file = None if file is None else Path(file)
        #: the file as this run wrote it (:func:`~flexbeam.results.files.file_stamp`; set by the stream that wrote it)
        self.file_stamp: tuple[int, int, int] | None = None
        self.summaries = dict(summaries or {})
        given = source is None and file is None
        self._samples = (np.asarray(time), np.asarray(phase), arrays) if given else None
        self._contacts = list(contacts or [])
        self._completed: set[int] = set()
        self.status, self.message = status, message
        self.stats = dict(stats or {})
        self._provenance = dict(provenance or {})
        self.measuring_points = np.empty(0) if measuring_points is None else np.asarray(measuring_points, float)
        self._force_at = force_at if source is None else source.force_at
        self.source = source
        self.motion = motion
        self._peaks: dict[int, list[tuple[float, float]]] = {}

    # ----------------------------------------------------------------- samples
    def _loaded(self) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
        if self._samples is None:
            if self.source is not None:
                self._samples = self.source.samples
            else:
                self._samples = export.read_samples(self.stored_file(), self.stored_file)
        return self._samples

    @property
    def samples_in_file(self) -> bool:
        """Are the output samples in the result ``file`` alone (a streamed run whose arrays nobody has asked for
        yet)?  Then a window of them can be read without the rest (:func:`~flexbeam.results.readback.read_window`)."""
        return self._samples is None and self.file is not None

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

    def provenance_entry(self, key: str) -> Any:
        """One provenance entry that is given, not deferred (None otherwise): the metrics read the beam's length
        without writing the case's TOML (0.2 ms a run)."""
        value = self._provenance.get(key)
        return None if callable(value) else value

    @property
    def contacts(self) -> list[ContactEvent]:
        """The contact log, each record completed (impulse, energies, peak) on first use."""
        for i in range(len(self._contacts)):
            self.contact(i)
        return self._contacts

    def contact(self, i: int) -> ContactEvent:
        """Contact record ``i``; a run's impulse, energies before/after and peak are found on its dense output
        the first time it is asked for (a jump's impulse and energies are logged at the jump)."""
        i = record_index(i, len(self._contacts))
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
            # friction under CCFM and CCM: int F_t dt over the contact, after CCM's onset jump (and Painlevé's)
            held = tangential_impulse(src.system, src.segments, ev.onset, end, ev.pair)
            if math.isnan(ev.tangential_impulse):
                ev.tangential_impulse = held
            elif not math.isnan(held):
                ev.tangential_impulse += held
            if not jumped:
                ev.energy_before = src.mechanical_energy(ev.onset, after=True)
            ev.energy_after = src.mechanical_energy(end)
        peak = self._largest_peak(i) if self.source is not None else None
        if peak is None:
            peaks = self.force_peaks(i, threshold=0.0)
            peak = max(peaks, key=lambda p: p[1]) if peaks else None
        if peak is not None:
            ev.peak_time, ev.peak_force = peak
        return ev

    def _largest_peak(self, i: int) -> tuple[float, float] | None:
        """The largest force of contact record ``i`` on a run's dense output, (time [s], force [N]): the local
        maxima of its nodal forces (:meth:`~flexbeam.results.arrays.RunSource.nodal_profile`, computed by the
        integrator) that could be the largest -- a smooth peak stands above its sampled value by less than that
        value stands above its lower neighbour -- refined by zooming to PEAK_XTOL.  Its cost is the contact's
        steps, not the run's.  None when the record has no force history (an IMM impact), or when its force is
        largest where the run ends inside it, still rising (the FE reference's records say so too)."""
        ev = self._contacts[i]
        assert self.source is not None
        end = ev.end if math.isfinite(ev.end) else self.source.run.t_final
        tt, f = self.source.nodal_profile(ev.onset, end, ev.pair)
        if tt.size < 3:
            return None
        idx = interior_maxima(f, start=True)
        if f.size > 1 and f[-1] > f[-2] and math.isfinite(ev.end):  # (a force still rising at t_end: no peak yet)
            idx.append(f.size - 1)
        if not idx:
            return None
        top = float(np.max(f))
        best: tuple[float, float] | None = None
        for k in idx:
            left, right = f[max(k - 1, 0)], f[min(k + 1, f.size - 1)]
            if f[k] + (f[k] - min(left, right)) < top:
                continue
            h = max(tt[k] - tt[max(k - 1, 0)], tt[min(k + 1, tt.size - 1)] - tt[k])
            cand = self._refine_max(float(tt[k]), h, ev.onset, end, ev.pair)
            if best is None or cand[1] > best[1]:
                best = cand
        return best

    @cached_property
    def _in_contact(self) -> np.ndarray:
        """Samples of contact, constrained or resting phases (bool per sample)."""
        return np.isin(self.phase, ("contact", "constrained", "resting"))

    def __getitem__(self, name: str) -> np.ndarray:
        return self.arrays[name]

    @property
    def method(self) -> str:
        return str(self._provenance.get("method", ""))

    @property
    def drive_frequency(self) -> float:
        """The fundamental frequency f [Hz] of the base's periodic drive (``base.frequency``), NaN without one."""
        return float(self._provenance.get("drive_frequency", math.nan))

    @property
    def records(self) -> list[ContactEvent]:
        """The contact records as logged (:attr:`contacts` completes them)."""
        return self._contacts

    @property
    def pair_labels(self) -> list[str]:
        """The obstacle of each contact pair (pair 0: ``"obstacle"``, the case's ``[obstacle]``)."""
        return list(self._provenance.get("contact_pairs") or ["obstacle"])

    @property
    def compliant_support(self) -> bool:
        """Does the obstacle stand on a compliant support (a sensor force)?"""
        return bool(self._provenance.get("compliant_support")) or (
            self._samples is not None and "sensor_force" in self.arrays
        )

    # ----------------------------------------------------------------- force peaks
    def _refine_max(self, t_guess: float, h: float, lo: float, hi: float, pair: int = 0) -> tuple[float, float]:
        if self.source is not None:
            return self.source.refine_pair_max(pair, t_guess, h, lo, hi)
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
        contact, threshold = record_index(contact, len(self._contacts)), nonnegative(threshold, "threshold")
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

    # ----------------------------------------------------------------- metrics (flexbeam.results.summary)
    def energy_drift(self) -> tuple[float, float]:
        """(end, max) relative change of the total energy (:func:`~flexbeam.results.summary.energy_drift`)."""
        return summary.energy_drift(self)

    def sensor_pulse(self, threshold: float = 0.05) -> tuple[list[tuple[float, float]], float]:
        """Peaks and duration of the first sensor-force pulse (:func:`~flexbeam.results.summary.sensor_pulse`)."""
        return summary.sensor_pulse(self, threshold)

    def contact_counts(self) -> ContactCounts:
        """The records sorted into contacts and micro-impacts (:func:`~flexbeam.results.summary.contact_counts`)."""
        return summary.contact_counts(self)

    def events(self, counts: ContactCounts | None = None) -> list[dict[str, Any]]:
        """One dict per contact record (:func:`~flexbeam.results.summary.events`)."""
        return summary.events(self, counts)

    @property
    def is_free(self) -> bool:
        """Is the beam a free one (``joint.kind = "free"``), which has collision episodes?"""
        return is_free(self)

    def episodes(self, gap: float | None = None) -> list[Episode]:
        """A free beam's collision episodes: G's velocity and spin before and after, their counts and apparent
        restitution (:func:`~flexbeam.results.episodes.find_episodes`; ``gap``: the free flight that ends an
        episode [s], default one period of the first free-free bending mode); [] for a beam on a joint."""
        return find_episodes(self, self.contact_counts(), positive_or_none(gap, "gap"))

    def poincare(self, phase: float = 0.0, discard: int = 0) -> dict[str, np.ndarray]:
        """The Poincaré section of a run on a moving base (:func:`~flexbeam.results.poincare.poincare`)."""
        from .poincare import poincare

        return poincare(self, phase, discard)

    def metrics(self) -> dict[str, Any]:
        """The run's summary numbers, the ``--json`` contract (:func:`~flexbeam.results.summary.run_metrics`)."""
        return summary.run_metrics(self)

    # ----------------------------------------------------------------- export (flexbeam.results.export)
    def to_xarray(self) -> xr.Dataset:
        """:class:`xarray.Dataset` with dims time, mode, point, contact (:func:`~flexbeam.results.export.to_xarray`;
        a streamed run's: its file, opened lazily)."""
        if self.file is not None:
            import xarray as xr

            return xr.open_dataset(self.stored_file())
        return export.to_xarray(self)

    def stored_file(self) -> Path:
        """A streamed run's result file, checked to be the one it wrote: a RuntimeError if another was written over
        it since (two runs streamed to one path in turn: the first's arrays read the second's samples, silently)."""
        assert self.file is not None
        if self.file_stamp is not None and (not self.file.exists() or file_stamp(self.file) != self.file_stamp):
            raise RuntimeError(
                f"{self.file}: the result file this run streamed to was replaced or removed since it was written; "
                "its samples are gone (stream each run to its own path)"
            )
        return self.file

    def to_netcdf(self, path: str | Path, time_chunk: int = export.TIME_CHUNK, quantize: bool = True) -> Path:
        """Write :meth:`to_xarray` to NetCDF-4 atomically, the outputs of the integrated state rounded to the
        integrator's precision unless ``quantize`` is False (:func:`~flexbeam.results.export.to_netcdf`)."""
        return export.to_netcdf(self, path, time_chunk, quantize)

    # ----------------------------------------------------------------- views (flexbeam.views, registered)
    #: the views' accessor class, registered by :mod:`flexbeam.views.accessor` when flexbeam is imported
    views: ClassVar[Callable[[Solution], Any] | None] = None

    def _views(self) -> Any:
        if Solution.views is None:
            raise RuntimeError("Solution: the views are registered by `import flexbeam` (flexbeam.views.accessor)")
        return Solution.views(self)

    @property
    def plot(self) -> Any:
        """Figures of this run: ``sol.plot("contact_force")``, ``sol.plot.normal_velocity()``, ...
        (:class:`flexbeam.views.accessor.SolutionViews`)."""
        return self._views()

    def animate(self, path: str | Path, **options: Any) -> Path:
        """Render an animation of this run to ``path`` (.gif or .mp4): the deformed beam with magnified
        deflection, the hub, the obstacle and the contact force, in slow motion through the contacts.

        ``options`` as for :func:`flexbeam.views.animation.animate` (``scale``, ``window``, ``frames``, ``fps``,
        ``size``, ...); returns the path written.
        """
        return self._views().animate(path, **options)

    def __repr__(self) -> str:
        """One line: the case, the method, the status and the records (no sample evaluated: Jupyter's view is HTML)."""
        name = self._provenance.get("case_name", "")
        return f"<Solution {name!r} {self.method}: {self.status}, {len(self._contacts)} contact records>"

    def _repr_html_(self) -> str:
        """Notebook display: status, metrics and a small plot (:func:`flexbeam.views.display.solution_html`)."""
        return self._views().html()
