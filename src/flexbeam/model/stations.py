"""The station tables of contact anywhere: the beam's shapes at equally spaced stations, which the kernels' search
for the surface point nearest an obstacle (``kernels/src/nearest.c``) interpolates by cubic Hermite polynomials.

Per station x_j: Psi, Psi', Psi'' (bending), H (the foreshortening's, first-order model) and, with axial modes
(``model.axial_modes``), Phi_a and Phi_a' -- the centre line is rho(x) = (r_h + x + Phi_a p - 1/2 q^T H q, Psi q)
(``docs/formulation.md``, *Axial deformation*).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import numerics as nm
from .beam import ModalBeam, _gauss


@dataclass(frozen=True)
class StationTable:
    """Mode shapes at equally spaced stations x_j along the beam, for the contact-anywhere search of the kernels
    (``kernels/src/nearest.c``, which interpolates them by cubic Hermite polynomials): Psi, Psi', Psi'' (stations x n),
    H (stations x n x n, H(x) = r_h d d^T + int_0^x Psi'^T Psi' in the first-order model, 0 in the zeroth), the
    largest |Psi_k| and |Psi'_k| over the beam (with a 5 % margin for the interpolation between stations), the
    surface offset c, and the axial shapes Phi_a, Phi_a' (stations x n_a) with the largest |Phi_a,k| (empty without
    axial modes)."""

    x: np.ndarray
    phi: np.ndarray
    dphi: np.ndarray
    ddphi: np.ndarray
    H: np.ndarray
    maxphi: np.ndarray
    maxdphi: np.ndarray
    surface: float
    aphi: np.ndarray | None = None
    daphi: np.ndarray | None = None
    maxaphi: np.ndarray | None = None


#: stations per wavelength of the highest mode: cubic Hermite interpolation is then exact to ~(2 pi / 32)^4 / 384
#: = 4e-6 of a shape's amplitude
STATIONS_PER_WAVE = 32


def station_table(beam: ModalBeam, surface: float) -> StationTable:
    """The :class:`StationTable` of ``beam`` (wavelength of bending mode n ~ 2 L / (n + 1/4), of axial mode k
    2 L / k or fewer); built once per beam and surface offset (the modal beam itself is memoised by
    :func:`~flexbeam.model.beam.build_modal_beam`)."""
    table = beam._tables.get(float(surface))
    if table is None:
        table = beam._tables[float(surface)] = _station_table(beam, float(surface))
    return table


def _station_table(beam: ModalBeam, surface: float) -> StationTable:
    n, L = beam.n, beam.length
    M = max(33, int(math.ceil(STATIONS_PER_WAVE * (max(n, beam.na) + 1) / 2)) + 1)
    x = np.linspace(0.0, L, M)
    fine = np.linspace(0.0, L, 8 * M)
    axial = {}
    if beam.axial is not None:
        shapes = beam.axial.shapes
        axial = {"aphi": np.ascontiguousarray(shapes(x, 0)), "daphi": np.ascontiguousarray(shapes(x, 1)),
                 "maxaphi": 1.05 * np.max(np.abs(shapes(fine, 0)), axis=0)}  # fmt: skip
    if n == 0:
        z = np.zeros((M, 0))
        return StationTable(x, z, z, z, np.zeros((M, 0, 0)), np.zeros(0), np.zeros(0), float(surface), **axial)
    phi, dphi, ddphi = (np.ascontiguousarray(beam.shapes(x, k)) for k in (0, 1, 2))
    H = np.zeros((M, n, n))
    if beam.first_order:
        acc = beam.hub_radius * np.outer(beam.d, beam.d) if beam.H_root is None else beam.H_root.copy()
        H[0] = acc
        for j in range(1, M):
            xg, wg = _gauss(x[j - 1], x[j], 24)
            d1 = beam.shapes(xg, 1)
            acc = acc + nm.gram(d1, wg)
            H[j] = 0.5 * (acc + acc.T)
    maxphi = 1.05 * np.max(np.abs(beam.shapes(fine, 0)), axis=0)
    maxdphi = 1.05 * np.max(np.abs(beam.shapes(fine, 1)), axis=0)
    return StationTable(x, phi, dphi, ddphi, H, maxphi, maxdphi, float(surface), **axial)


__all__ = ["StationTable", "station_table"]
