"""The joint that holds the beam: its kind and its drive (docs/architecture.md, *Adding a joint kind*)."""

from __future__ import annotations

import math
from functools import cached_property
from pathlib import Path
from typing import Literal

import numpy as np
from pydantic import Field, field_validator, model_validator

from ..errors import not_text
from .fields import Bounded, Finite, Positive, Rate, Section


class Joint(Section):
    """The joint that carries the beam's floating frame.

    * ``revolute``: a revolute joint at the fixed point O (the origin); the hub of ``[hub]`` turns about it, as
      ``[drive]`` says.
    * ``free``: no joint, a free-flying beam: its centre of mass (x_G, y_G) and angle theta are free coordinates
      under gravity, the frame at the centre of mass with the free-free bending modes (``docs/formulation.md``, *A
      free-flying beam*); no hub and no drive.  Its start: ``[initial]`` ``state`` (``position``, ``velocity``,
      ``angle``, ``rate``) or ``impact``.
    """

    kind: Literal["revolute", "free"] = Field(
        "revolute",
        description="joint kind: 'revolute' (a revolute joint at O) or 'free' (no joint: a free-flying beam)",
    )


class Drive(Section):
    """What happens at the joint O.

    * ``free``: no torque (tau = 0).
    * ``torque``: constant driving torque ``torque`` [N m].
    * ``prescribed``: theta(t) given by ``profile``: ``"constant-rate"``
      (theta = theta_0 + ``spin_rate`` t) or ``"kane-spinup"`` (Kane, Ryan & Banerjee
      1987: theta = (W/T)[t^2/2 + (T/2 pi)^2 (cos(2 pi t/T) - 1)] for t < T, then
      constant rate W = ``spin_rate``, T = ``spin_up_time``).
    """

    kind: Literal["free", "torque", "prescribed"] = "free"
    torque: Finite = Field(0.0, description="constant joint torque tau [N m] (kind = torque)")
    profile: Literal["constant-rate", "kane-spinup"] = "constant-rate"
    spin_rate: Rate = Field(0.0, description="final spin rate Omega_s [rad/s]")
    spin_up_time: Positive = Field(15.0, description="spin-up time T_s [s] (kane-spinup)")


class Harmonic(Section):
    """One harmonic of the base's motion along an axis: ``amplitude`` sin(2 pi ``order`` f t + ``phase``), f the
    base's fundamental ``frequency``."""

    axis: Literal["x", "y"] = Field(description="the inertial axis the joint O moves along")
    amplitude: Bounded(-1e3, 1e3) = Field(description="displacement amplitude [m] (|A| <= 1e3 m)")
    order: int = Field(1, ge=1, le=1000, description="multiple k of the fundamental frequency (1..1000)")
    phase: Bounded(-1e3, 1e3) = Field(0.0, description="phase [rad]")


class Base(Section):
    """A moving base: the joint O moves in the plane as prescribed (a cantilever on a shaker).

    ``r_O(t) = sum over harmonics of A_i sin(2 pi k_i f t + phi_i) e_axis + 1/2 acceleration t^2 + T(t)``, the
    harmonics' fundamental ``frequency`` f [Hz] (the drive's period 1/f is that of its Poincare map), T(t) the
    ``table``'s interpolant: the not-a-knot C2 cubic spline through its rows (t, x, y) along each axis, so that a_O
    is continuous and the jerk, constant between rows, exists for the base's work.  The rows (at least 4, times
    increasing, finite) may be given inline or as the path of a CSV file of three columns t, x, y (a header line and
    ``#`` comments allowed; relative to the case file); they must cover the run, 0 <= t <= ``solver.t_end``: a
    table is not extrapolated.  The equations are
    written in the base frame (origin at O, axes parallel to the inertial ones), where the base's motion acts as the
    uniform inertial field g_eff(t) = (0, -g) - a_O(t) on the beam (docs/formulation.md, *A moving base*); an
    obstacle is carried by the base (it moves with O) unless its ``fixed_to = "ground"``.  No harmonic and no
    acceleration: a fixed joint, today's model bit for bit.  A revolute joint only.
    """

    frequency: Positive | None = Field(None, description="fundamental frequency f of the harmonics [Hz]")
    harmonics: list[Harmonic] = Field(default_factory=list, description="the harmonics of r_O(t) (at most 12)")
    acceleration: tuple[Bounded(-1e6, 1e6), Bounded(-1e6, 1e6)] = Field(
        (0.0, 0.0), description="a constant acceleration of O [m/s^2] (|a| <= 1e6 per axis)"
    )
    table: list[tuple[float, float, float]] | None = Field(
        None,
        description="rows (t [s], x [m], y [m]) of O's motion, or a CSV file of them, interpolated by a cubic "
        "spline (at least 4 rows, times increasing, covering 0 .. solver.t_end)",
    )

    @property
    def moving(self) -> bool:
        """Does the joint O move (a harmonic of nonzero amplitude, an acceleration or a table)?"""
        table = self.table is not None and any(x != 0.0 or y != 0.0 for _, x, y in self.table)
        return any(h.amplitude != 0.0 for h in self.harmonics) or any(a != 0.0 for a in self.acceleration) or table

    @property
    def drive(self) -> dict[str, float]:
        """``{"drive_frequency": f}`` [Hz] of a base shaken periodically (``frequency``), for the drive phase of the
        contact records (the runs' provenance); empty without one."""
        return {"drive_frequency": float(self.frequency)} if self.moving and self.frequency is not None else {}

    @cached_property
    def spline(self):
        """The table's interpolant T(t) = (x, y), scipy's not-a-knot ``CubicSpline`` through its rows (None: no
        table)."""
        if self.table is None:
            return None
        from scipy.interpolate import CubicSpline  # scipy only where a table is used: the CLI starts without it

        rows = np.asarray(self.table, float)
        return CubicSpline(rows[:, 0], rows[:, 1:], bc_type="not-a-knot")

    @field_validator("table", mode="before")
    @classmethod
    def _read_table(cls, value):
        """A CSV path read into rows; each row three numbers."""
        if isinstance(value, (str, Path)):
            value = read_table(Path(value))
        if value is None:
            return None
        if not isinstance(value, (list, tuple)):
            raise ValueError("base.table: rows (t, x, y) or the path of a CSV file of them")
        for i, row in enumerate(value):
            if not isinstance(row, (list, tuple)) or len(row) != 3:
                raise ValueError(f"base.table: row {i}: expected three numbers (t, x, y), got {row!r}")
        return value

    @field_validator("table", mode="after")
    @classmethod
    def _check_table(cls, rows):
        if rows is None:
            return None
        if len(rows) < 4:
            raise ValueError(f"base.table: at least 4 rows (t, x, y) for the cubic spline, not {len(rows)}")
        for i, row in enumerate(rows):
            if not all(math.isfinite(v) for v in row):
                raise ValueError(f"base.table: row {i}: must be finite numbers (got {row})")
            if i and not row[0] > rows[i - 1][0]:
                raise ValueError(
                    f"base.table: the times must increase (row {i}: t = {row[0]:g} after {rows[i - 1][0]:g})"
                )
        if len(rows) > 100_000:
            raise ValueError(f"base.table: at most 100000 rows, not {len(rows)}")
        return rows

    def motion(self, t: float) -> tuple[tuple[float, float], tuple[float, float], tuple[float, float]]:
        """(r_O, v_O, a_O) at time ``t`` [s] (the compiled kernels evaluate it in ``base_motion.c``)."""
        ax, ay = self.acceleration
        r, v, a = [0.5 * ax * t * t, 0.5 * ay * t * t], [ax * t, ay * t], [ax, ay]
        for h in self.harmonics:
            k, w = int(h.axis == "y"), 2.0 * math.pi * h.order * (self.frequency or 0.0)
            s, c = math.sin(w * t + h.phase), math.cos(w * t + h.phase)
            r[k] += h.amplitude * s
            v[k] += h.amplitude * w * c
            a[k] -= h.amplitude * w * w * s
        if self.spline is not None:
            for d, out in enumerate((r, v, a)):
                value = self.spline(t, d)
                out[0] += float(value[0])
                out[1] += float(value[1])
        return (r[0], r[1]), (v[0], v[1]), (a[0], a[1])

    @model_validator(mode="after")
    def _frequency_given(self) -> Base:
        if self.harmonics and self.frequency is None:
            raise ValueError("base.frequency: required with base.harmonics (a frequency > 0 in Hz)")
        if len(self.harmonics) > 12:
            raise ValueError(f"base.harmonics: at most 12, not {len(self.harmonics)}")
        return self


def read_table(path: Path) -> list[list[float]]:
    """The rows (t, x, y) of a CSV file: three comma-separated numbers a line; blank lines, ``#`` comments and a first
    line that is not numbers (a header) skipped.  Raises ValueError naming ``base.table``."""
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except OSError as exc:
        raise ValueError(f"base.table: cannot read '{path}': {exc.strerror}") from None
    except UnicodeDecodeError as exc:
        raise ValueError(not_text("base.table", path, "CSV", exc)) from None
    rows: list[list[float]] = []
    for number, line in enumerate(lines, 1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        try:
            row = [float(v) for v in text.split(",")]
        except ValueError:
            if not rows and number == next(i for i, ln in enumerate(lines, 1) if ln.split("#", 1)[0].strip()):
                continue  # a header
            raise ValueError(f"base.table: '{path}' line {number}: not numbers: {text!r}") from None
        if len(row) != 3:
            raise ValueError(f"base.table: '{path}' line {number}: expected three columns t, x, y, got {len(row)}")
        rows.append(row)
    return rows
