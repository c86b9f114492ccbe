"""The summary numbers of a run (:meth:`Solution.metrics <flexbeam.results.solution.Solution.metrics>`, the
``--json`` contract of ``flexbeam run``): energy balance, the first contact's force peaks, impulse and velocities,
the contact counts, the sensor pulse, one record per contact.  Names, units and kinds are those of the registry
:data:`flexbeam.results.metrics.METRICS`.
"""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import FlexbeamWarning
from .counts import ContactCounts, classify_contacts
from .episodes import find_episodes
from .metrics import METRICS, OPTIONAL_SCOPES
from .peaks import interior_maxima
from .poincare import drive_phase

if TYPE_CHECKING:
    from .solution import Solution


def energy_drift(sol: Solution) -> tuple[float, float]:
    """(end, max) relative change of the total energy.

    Relative to ``max(|E(0)|, max_t T(t))`` so that a zero gravitational reference does not divide by
    zero.  With a run's dense output the energies are those at every step boundary, else at the samples; a streamed
    run tallied them as it went.
    """
    if "energy_drift" in sol.summaries:
        return sol.summaries["energy_drift"]
    if sol.source is not None:
        _, E, T = sol.source.checkpoints
    else:
        E, T = sol.arrays["total_energy"], sol.arrays["kinetic_energy"]
    if E.size == 0:
        return math.nan, math.nan
    scale = max(abs(E[0]), float(np.max(T)), 1e-300)
    return float((E[-1] - E[0]) / scale), float(np.max(np.abs(E - E[0])) / scale)


def sensor_pulse(sol: Solution, threshold: float = 0.05) -> tuple[list[tuple[float, float]], float]:
    """Peaks (time [s], force [N]) and duration [s] of the first sensor-force pulse.

    Compliant support only.  Like the experiment, which "determined the beginning and ending of the impact
    by the sign of the impact force" (Duan et al. 2013, Sec. 4), the pulse runs from the first contact's
    onset until the sensor force -(k_s s + c_s s') first returns to zero (linear interpolation between
    samples); its peaks are the sampled local maxima above ``threshold`` x its maximum.  A streamed run collected
    the pulse's samples as it went, and a run in memory evaluates them alone (:meth:`RunSource.sensor_pulse
    <flexbeam.results.arrays.RunSource.sensor_pulse>`); a Solution read from a file reads them off its samples.
    """
    summaries, source = getattr(sol, "summaries", {}), getattr(sol, "source", None)
    if "sensor_pulse" in summaries or source is not None:
        if "sensor_pulse" in summaries:
            peaks, duration = summaries["sensor_pulse"]
        elif source.system.compliant:
            peaks, duration = source.sensor_pulse(sol.records[:1])
        else:
            return [], math.nan
        top = max((p[1] for p in peaks), default=0.0)
        return [p for p in peaks if p[1] > threshold * top], duration
    if "sensor_force" not in sol.arrays or not sol.records:
        return [], math.nan
    onset = sol.records[0].onset
    t, f = sol.time, sol.arrays["sensor_force"]
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


def contact_metrics(sol: Solution, i: int | None) -> dict[str, Any]:
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
    ev = sol.contact(i)
    out.update(
        impact_velocity=ev.velocity_before,
        post_impact_velocity=ev.velocity_after,
        contact_duration=ev.duration,
        impulse=ev.impulse,
        energy_before=ev.energy_before,
        energy_after=ev.energy_after,
    )
    peaks = sol.force_peaks(i)
    end = ev.end if math.isfinite(ev.end) else math.inf
    if peaks:
        tp, fp = max(peaks, key=lambda p: p[1])
        others = [p[1] for p in peaks if p[0] != tp]
        # the record's peak where it is the same maximum (inside the contact, the value the same to 1e-9 where the
        # two searches agree to ~1e-13): one number for it, the record's (events[i])
        if ev.onset < ev.peak_time < end and abs(ev.peak_force - fp) <= 1e-9 * fp:
            peaks = [(ev.peak_time, ev.peak_force) if p[0] == tp else p for p in peaks]
        out.update(
            force_peaks=[p[1] for p in peaks],
            force_peak_times=[p[0] - ev.onset for p in peaks],
            second_peak_force=max(others) if others else math.nan,
        )
    if math.isfinite(ev.peak_force):  # the record's peak (the first record's, as the docs say), not a second search
        out.update(peak_force=ev.peak_force, peak_time=ev.peak_time - ev.onset)
    elif peaks:
        out.update(peak_force=fp, peak_time=tp - ev.onset)
    return out


def contact_counts(sol: Solution) -> ContactCounts:
    """The contact records sorted into contacts and micro-impacts, the micro-impacts grouped into chatter
    episodes: :func:`flexbeam.results.counts.classify_contacts` on every record's impulse and approach speed
    (docs/methods.md, *What one contact is*)."""
    c = sol.contacts
    return classify_contacts(
        [ev.pair for ev in c], [ev.impulse for ev in c], [-ev.velocity_before for ev in c], len(sol.pair_labels)
    )


def events(sol: Solution, counts: ContactCounts | None = None) -> list[dict[str, Any]]:
    """One dict per contact record, in the order of their onsets (the ``events`` of :func:`run_metrics`).

    ``index`` (the record's place in :attr:`contacts`), ``pair``, ``obstacle``, ``onset``, ``end`` [s],
    ``duration`` [s], ``peak_force`` [N] and ``peak_time`` [s after the onset] (NaN without a force
    history: an IMM impact), ``velocity_before``, ``velocity_after`` [m/s] (P's normal velocity, negative
    approaching), ``impulse`` [N s], ``kind`` (``"contact"`` or ``"micro-impact"``) and ``chatter_episode``
    (the micro-impact's episode, None for a contact), ``tangential_impulse`` [N s] (a frictional impact's; NaN
    without friction) and ``drive_phase`` (the onset's phase of a periodic base drive, frac(f t) in [0, 1); NaN
    without one);
    ``counts``: :func:`contact_counts`, if already known.
    """
    counts = contact_counts(sol) if counts is None else counts
    labels, f = sol.pair_labels, sol.drive_frequency
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
            "tangential_impulse": ev.tangential_impulse,
            "drive_phase": drive_phase(ev.onset, f) if math.isfinite(f) else math.nan,
        }
        for i, ev in enumerate(sol.contacts)
    ]


def run_metrics(sol: Solution) -> dict[str, Any]:
    """The run's summary numbers (the ``--json`` contract of ``flexbeam run``), in the order, units and
    meaning of the registry :data:`flexbeam.results.metrics.METRICS` (NaN or an empty list when not defined).

    ``peak_force`` [N], ``peak_time`` [s after the first onset], ``contact_duration`` [s], ``force_peaks``
    (list of local maxima [N] above 5 % of the peak) with ``force_peak_times`` [s after onset],
    ``contacts`` (the records that are not micro-impacts, :func:`contact_counts`) with ``contact_records``,
    ``micro_impacts`` and ``chatter_episodes``, ``post_impact_velocity`` (P's normal velocity at the end of
    the first contact [m/s], positive away from the obstacle), ``energy_drift``, ``wall_time`` [s],
    ``steps``; the per-contact ones are those of the first contact record of pair 0 (``[contact]`` against
    ``[obstacle]``); ``pairs`` lists, for every pair, its counts and its first record's metrics (the same
    keys for every pair, NaN and empty lists for a pair that never touched); ``events`` lists every record
    (:func:`events`); with a compliant obstacle support also ``sensor_peak_force``,
    ``sensor_second_peak_force`` [N] and ``sensor_duration`` [s] of the first sensor-force pulse
    (:func:`sensor_pulse`); for a free beam (``joint.kind = "free"``) also ``episodes``, one record per
    collision episode (:func:`flexbeam.results.episodes.find_episodes`), their number ``collision_episodes`` and the
    first one's ``episode_contacts``, ``episode_micro_impacts`` and apparent restitution ``restitution_newton``,
    ``restitution_poisson``, ``restitution_energetic`` (NaN without an episode).
    """
    drift, drift_max = energy_drift(sol)
    out: dict[str, Any] = {
        name: ([] if m.kind in ("numbers", "records") else math.nan)
        for name, m in METRICS.items()
        if m.scope not in OPTIONAL_SCOPES
    }
    counts = contact_counts(sol)
    out.update(
        method=sol.method,
        status=sol.status,
        message=sol.message,
        **counts.of_pair(None),
        energy_drift=drift,
        energy_drift_max=drift_max,
        wall_time=sol.stats.get("wall_time", math.nan),
        steps=int(sol.stats.get("steps", 0)),
        nfev=int(sol.stats.get("nfev", 0)),
    )
    labels = sol.pair_labels
    firsts = [next((i for i, ev in enumerate(sol.records) if ev.pair == k), None) for k in range(len(labels))]
    if firsts[0] is not None:
        out.update(contact_metrics(sol, firsts[0]))
    out["pairs"] = [
        {"pair": k, "obstacle": label, **counts.of_pair(k), **contact_metrics(sol, i)}
        for k, (label, i) in enumerate(zip(labels, firsts))
    ]
    out["events"] = events(sol, counts)
    if sol.compliant_support:
        peaks, duration = sensor_pulse(sol)
        ranked = sorted((p[1] for p in peaks), reverse=True)
        out["sensor_peak_force"] = ranked[0] if ranked else math.nan
        out["sensor_second_peak_force"] = ranked[1] if len(ranked) > 1 else math.nan
        out["sensor_duration"] = duration
    if sol.is_free:
        out.update(episode_metrics(sol, counts))
    if "tip_deflection" in sol.summaries:
        out["tip_deflection_min"], out["tip_deflection_max"] = sol.summaries["tip_deflection"]
    elif sol.source is not None:
        out["tip_deflection_min"], out["tip_deflection_max"] = sol.source.extremes("tip_deflection")
    elif "tip_deflection" in sol.arrays and sol.arrays["tip_deflection"].size:
        out["tip_deflection_min"] = float(np.min(sol.arrays["tip_deflection"]))
        out["tip_deflection_max"] = float(np.max(sol.arrays["tip_deflection"]))
    warn_large_deflection(out, sol.provenance_entry("beam_length"))
    # in the registry's order, the optional scopes' keys in their places (a compliant support's sensor_* came last)
    return {**{k: out[k] for k in METRICS if k in out}, **{k: v for k, v in out.items() if k not in METRICS}}


#: the tip's elastic deflection, as a share of the beam's length, beyond which the modal model's small-deflection
#: terms err by more than ~1 %: its curvature (w'' for w'' / (1 + w'^2)^(3/2)) and the foreshortening it keeps to
#: second order are both off by ~ w'^2, and a cantilever's first mode has w' = 1.38 w / L at the tip: 2 % at 0.1 L
LARGE_DEFLECTION = 0.1


def warn_large_deflection(out: dict[str, Any], length: float | None) -> None:
    """Warn (:class:`~flexbeam.errors.FlexbeamWarning`) where the tip's elastic deflection in ``out`` exceeds
    :data:`LARGE_DEFLECTION` of the beam's ``length`` (a modal run's provenance; the FE reference, geometrically
    exact, has none): a shaker at 10 m amplitude swung a 0.3 m beam's tip 35 m off its line, reported as a success
    (an exploratory hunt)."""
    ends = [abs(v) for v in (out["tip_deflection_min"], out["tip_deflection_max"]) if math.isfinite(v)]
    if not length or not ends or max(ends) <= LARGE_DEFLECTION * length:
        return
    d = max(ends)
    warnings.warn(
        f"tip_deflection: the tip's elastic deflection reaches {d:.3g} m = {d / length:.3g} beam.length, beyond the "
        f"small deflections of the modal model (its curvature and foreshortening err by ~ the slope squared: ~2 % at "
        f"{LARGE_DEFLECTION:g} beam.length); compare with the geometrically exact FE reference (--method fem)",
        FlexbeamWarning,
        stacklevel=3,
    )


def episode_metrics(sol: Solution, counts: ContactCounts | None = None) -> dict[str, Any]:
    """The metrics of a free beam's collision episodes (scope ``free`` of the registry): ``collision_episodes``,
    the first episode's counts and apparent restitution (NaN without one) and ``episodes``, one dict per episode
    (:meth:`flexbeam.results.episodes.Episode.record`)."""
    found = find_episodes(sol, contact_counts(sol) if counts is None else counts)
    first = found[0] if found else None
    return {
        "collision_episodes": len(found),
        "episode_contacts": first.contacts if first else 0,
        "episode_micro_impacts": first.micro_impacts if first else 0,
        "restitution_newton": first.restitution_newton if first else math.nan,
        "restitution_poisson": first.restitution_poisson if first else math.nan,
        "restitution_energetic": first.restitution_energetic if first else math.nan,
        "episodes": [ep.record(sol.pair_labels) for ep in found],
    }
