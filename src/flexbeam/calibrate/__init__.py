"""Calibration: least-squares fit of case parameters to measured impacts.

Two kinds of measurement, which may be combined:

* **histories** -- a CSV file with a time column and a contact-force and/or a
  normal-velocity column (SI units: s, N, m/s; velocity positive away from the
  obstacle, as ``normal_velocity``).  Data and model are aligned on the first contact:
  both time axes are shifted to the instant the force first reaches 10 % of the
  measured peak (linear interpolation between samples; without a force column the
  data's time is taken as time since the onset), and a remaining time shift is
  fitted with the parameters (a nuisance parameter within one contact duration,
  reported as ``time_shift``).
  The model's samples are interpolated linearly onto the data times.  Residuals are
  divided by the channel's largest measured magnitude.
* **features** -- summary numbers such as ``peak_force=584``; residuals are relative,
  ``(model - measured) / |measured|``.  A trial whose force has no second peak counts
  ``second_peak_force = 0`` (the limit of a vanishing shoulder).

The fit is :func:`scipy.optimize.least_squares` (trust-region reflective) in scaled
variables: ``z = ln(x / x0)`` for a field that is positive without an upper limit
(stiffness, moduli), ``z = (x - x0) / s`` otherwise, with ``s`` the allowed range when
the field has one (restitution: [0, 1]) and the field's range as bounds.  The
standard uncertainty of the fitted values is ``sqrt(diag(C))`` with
``C = sigma^2 (J^T J)^-1`` in the scaled variables mapped back to the fields
(``J``: finite-difference Jacobian at the solution, ``sigma^2 = |r|^2 / (m - p)``).
It assumes independent residuals of equal variance, so with histories it is only
as good as the noise is white; with as many features as parameters it is undefined.

The simulated time is cut to what the measurements need (the first contact and its
aftermath for first-contact features, the data's span for histories) unless
``solver.t_end`` is already shorter.

* :mod:`~flexbeam.calibrate.measured` -- :class:`Measured` histories from CSV, feature names;
* :mod:`~flexbeam.calibrate.fields` -- :class:`Parameter`: a fitted field, its range and scaling;
* :mod:`~flexbeam.calibrate.problem` -- the residuals of one calibration and :func:`covariance`;
* :mod:`~flexbeam.calibrate.result` -- :class:`Calibration`, its JSON report, files and plot;
* :mod:`~flexbeam.calibrate.fitting` -- :func:`calibrate`.
"""

from __future__ import annotations

from .._namespace import public_dir
from ..results.metrics import FEATURES, FIRST_CONTACT_FEATURES, SECOND_PEAKS
from .fields import Parameter, parse_fit
from .fitting import calibrate
from .measured import ROLES, Measured, parse_columns, parse_features, read_measured
from .problem import ResidualProblem, covariance
from .result import Calibration

__all__ = [
    "FEATURES",
    "FIRST_CONTACT_FEATURES",
    "ROLES",
    "SECOND_PEAKS",
    "Calibration",
    "Measured",
    "Parameter",
    "ResidualProblem",
    "calibrate",
    "covariance",
    "parse_columns",
    "parse_features",
    "parse_fit",
    "read_measured",
]

__dir__ = public_dir(globals())
