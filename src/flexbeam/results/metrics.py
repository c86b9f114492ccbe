"""The run metrics by name: one registry that ``Solution.metrics``, the ``--json`` output, sweeps and calibration
read.  The names are a contract users script against: add, never rename.

Each metric has its units, a long name, a kind (``number``, ``count``, ``numbers`` for a list, ``text``,
``records`` for a list of dicts: per pair, per contact record) and a
scope: ``first contact`` (computed from the first contact alone; a calibration of such features may stop the run
after it), ``sensor`` (the first sensor pulse of a compliant obstacle support: present only with one), ``free``
(the collision episodes of a free beam, :mod:`flexbeam.results.episodes`: present only for ``joint.kind =
"free"``), ``run``.
``fittable`` metrics can be calibration features; ``second_peak`` ones read 0 in a fit when a trial's force has a
single peak (the limit of a vanishing shoulder).

What counts as one contact (``contacts``, against ``contact_records``, ``micro_impacts`` and ``chatter_episodes``)
is defined once, in :mod:`flexbeam.results.counts` (docs/methods.md, *What one contact is*).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Metric:
    units: str
    long_name: str
    kind: str = "number"
    scope: str = "first contact"
    fittable: bool = True
    second_peak: bool = False


METRICS: dict[str, Metric] = {
    "method": Metric("", "Impact method", "text", "run", False),
    "status": Metric("", "Status of the run", "text", "run", False),
    "message": Metric("", "Why the run ended", "text", "run", False),
    "contacts": Metric(
        "1",
        "Number of contacts: records whose impulse or approach speed is >= 1 % of the pair's largest",
        "count",
        "run",
    ),
    "contact_records": Metric("1", "Number of contact records (contacts and micro-impacts)", "count", "run", False),
    "micro_impacts": Metric(
        "1",
        "Number of micro-impacts: records whose impulse and approach speed are < 1 % of the pair's largest",
        "count",
        "run",
        False,
    ),
    "chatter_episodes": Metric(
        "1", "Number of chatter episodes (runs of consecutive micro-impacts)", "count", "run", False
    ),
    "impact_velocity": Metric("m/s", "Normal velocity of P before the first contact"),
    "peak_force": Metric("N", "Peak force of the first contact"),
    "peak_time": Metric("s", "Time of the peak force after the first onset"),
    "contact_duration": Metric("s", "Duration of the first contact"),
    "force_peaks": Metric(
        "N", "Local force maxima of the first contact above 5 % of its peak", "numbers", fittable=False
    ),
    "force_peak_times": Metric("s", "Times of those maxima after the first onset", "numbers", fittable=False),
    "second_peak_force": Metric("N", "Second-largest force peak of the first contact", second_peak=True),
    "post_impact_velocity": Metric("m/s", "Normal velocity of P at the end of the first contact"),
    "impulse": Metric("N s", "Impulse of the first contact"),
    "energy_drift": Metric("1", "Relative change of the total energy at the end", scope="run", fittable=False),
    "energy_drift_max": Metric("1", "Largest relative change of the total energy", scope="run", fittable=False),
    "wall_time": Metric("s", "Integration wall time", scope="run", fittable=False),
    "steps": Metric("1", "Integrator steps", "count", "run", False),
    "nfev": Metric("1", "Right-hand side evaluations", "count", "run", False),
    "energy_before": Metric("J", "Mechanical energy before the first contact"),
    "energy_after": Metric("J", "Mechanical energy after the first contact"),
    "sensor_peak_force": Metric("N", "Peak force of the first sensor pulse", scope="sensor"),
    "sensor_second_peak_force": Metric(
        "N", "Second-largest peak of the first sensor pulse", scope="sensor", second_peak=True
    ),
    "sensor_duration": Metric("s", "Duration of the first sensor pulse (force > 0)", scope="sensor"),
    "tip_deflection_min": Metric("m", "Smallest tip deflection", scope="run"),
    "tip_deflection_max": Metric("m", "Largest tip deflection", scope="run"),
    "pairs": Metric("", "Per contact pair: its counts and its first contact's metrics", "records", "run", False),
    "events": Metric("", "Per contact record: times, peak force, velocities, impulse, kind", "records", "run", False),
    # a free beam's collision episodes (docs/free-beam.md, *Collision episodes*)
    "collision_episodes": Metric("1", "Number of collision episodes (free beam)", "count", "free", False),
    "episode_contacts": Metric("1", "Contacts in the first collision episode", "count", "free", False),
    "episode_micro_impacts": Metric("1", "Micro-impacts in the first collision episode", "count", "free", False),
    "restitution_newton": Metric(
        "1",
        "Apparent restitution of the first episode, Newton's (rigid-body normal velocities)",
        scope="free",
        fittable=False,
    ),
    "restitution_poisson": Metric(
        "1",
        "Apparent restitution of the first episode, Poisson's (restitution / compression impulse)",
        scope="free",
        fittable=False,
    ),
    "restitution_energetic": Metric(
        "1",
        "Apparent restitution of the first episode, Stronge's energetic (sqrt(-W_r / W_c))",
        scope="free",
        fittable=False,
    ),
    "episodes": Metric(
        "",
        "Per collision episode of a free beam: G's velocity and spin before and after, counts, restitution",
        "records",
        "free",
        False,
    ),
}

#: scopes of metrics present only for some runs (a compliant obstacle support, a free beam)
OPTIONAL_SCOPES = ("sensor", "free")
#: metrics that are plain numbers (variables of a sweep's Dataset)
SCALARS = tuple(k for k, m in METRICS.items() if m.kind in ("number", "count"))
#: metrics a calibration can fit as features
FEATURES = tuple(k for k, m in METRICS.items() if m.fittable and m.kind in ("number", "count"))
#: features of the first contact (and the first sensor pulse) alone
FIRST_CONTACT_FEATURES = tuple(k for k in FEATURES if METRICS[k].scope in ("first contact", "sensor"))
#: features that read 0 when a trial's force has a single peak
SECOND_PEAKS = tuple(k for k, m in METRICS.items() if m.second_peak)
#: features that a measurement gives > 0: the first contact's forces, duration and impulse, the sensor pulse's
POSITIVE_FEATURES = tuple(
    k for k in FIRST_CONTACT_FEATURES if METRICS[k].units in ("N", "N s") or k.endswith("duration")
)
