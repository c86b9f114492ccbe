"""Running summaries of a streamed run (:mod:`flexbeam.results.stream`): the energy balance over its step
boundaries and the first sensor-force pulse, fed segment by segment."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from .records import ContactEvent
from .summary import sensor_pulse

#: samples of the first sensor-force pulse kept (16 MB); a pulse not over by then ends there (its duration NaN)
PULSE_SAMPLES = 2**20


class EnergyTally:
    """The energy balance of :func:`~flexbeam.results.summary.energy_drift`, checkpoint batch by batch."""

    def __init__(self) -> None:
        self.E0: float | None = None
        self.deviation = 0.0
        self.kinetic = -math.inf
        self.last = math.nan

    def add(self, E: np.ndarray, T: np.ndarray) -> None:
        if not E.size:
            return
        if self.E0 is None:
            self.E0 = E[0]
        self.deviation = max(self.deviation, np.max(np.abs(E - self.E0)))
        self.kinetic = max(self.kinetic, float(np.max(T)))
        self.last = E[-1]

    def drift(self) -> tuple[float, float]:
        """(end, max) relative change of the total energy."""
        if self.E0 is None:
            return math.nan, math.nan
        scale = max(abs(self.E0), self.kinetic, 1e-300)
        return float((self.last - self.E0) / scale), float(self.deviation / scale)


class SensorPulse:
    """The samples of the first sensor-force pulse (:func:`~flexbeam.results.summary.sensor_pulse`), collected from
    the first contact's onset until the force has been positive and returns to zero (at most
    :data:`PULSE_SAMPLES`)."""

    def __init__(self, contacts: list[ContactEvent]) -> None:
        self.contacts = contacts
        self.tail: tuple[np.ndarray, np.ndarray] | None = None  # the last batch before the first onset
        self.t: list[np.ndarray] = []
        self.f: list[np.ndarray] = []
        self.size = 0
        self.positive = False
        self.done = False

    def feed(self, t: np.ndarray, f: np.ndarray) -> None:
        if self.done:
            return
        if not self.contacts:
            self.tail = (t.copy(), f.copy())
            return
        if self.tail is not None:
            tail, self.tail = self.tail, None
            self.feed(*tail)
        keep = t >= self.contacts[0].onset
        t, f = t[keep], f[keep]
        if not self.positive:
            pos = np.nonzero(f > 0.0)[0]
            if pos.size:
                self.positive = True
                back = np.nonzero(f[pos[0] :] <= 0.0)[0]
                stop = pos[0] + back[0] + 1 if back.size else None
            else:
                stop = None
        else:
            back = np.nonzero(f <= 0.0)[0]
            stop = back[0] + 1 if back.size else None
        if stop is not None:
            t, f = t[:stop], f[:stop]
            self.done = True
        room = PULSE_SAMPLES - self.size
        if t.size > room:
            t, f = t[:room], f[:room]
            self.done = True
        self.t.append(t.copy())
        self.f.append(f.copy())
        self.size += t.size

    def result(self) -> tuple[list[tuple[float, float]], float]:
        if not self.contacts or not self.t:
            return [], math.nan
        samples = SimpleNamespace(
            arrays={"sensor_force": np.concatenate(self.f)}, records=self.contacts[:1], time=np.concatenate(self.t)
        )
        return sensor_pulse(samples, threshold=0.0)  # every positive peak: the metrics choose theirs


__all__ = ["EnergyTally", "SensorPulse"]
