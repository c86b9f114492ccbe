"""The FE reference's structural damping of the beam (Numba), written for the co-rotational element on its own.

* **Kelvin-Voigt** (``beam.kelvin_voigt`` = c): the element's deformation rates -- the stretching rate u' = l' and
  the local end rotations' rates theta_i' = psi_i' - beta' of Crisfield's chord frame (:mod:`flexbeam.fem.element`),
  i.e. B z_e' -- carry the stress resultants c [EA u' / l0, (EI / l0) (4 theta_1' + 2 theta_2'), (EI / l0)
  (2 theta_1' + 4 theta_2')], so the damping force is f = c B^T D B z_e' (beta K_elastic on the deformation rates:
  it vanishes in a rigid motion, whatever the frame); its velocity tangent is c B^T D B.
* **Viscous per unit length** (``beam.viscous_damping`` = eta): a force -eta v_rel per unit length, v_rel the
  velocity of the material point relative to the hub frame (origin O, turning with theta): v_rel = G (z_e' - theta'
  w_e), w_e = (-Y_A, X_A, 1, -Y_B, X_B, 1) the nodal velocities of a unit rigid rotation about O (the interpolated
  field turns rigidly with them), so f = (eta / mu) M_e (z_e' - theta' w_e), M_e = int mu G^T G dx the element's
  mass matrix.  It acts between the beam and the hub (internal): its generalised force on theta is the reaction
  -sum w . f over the nodes (the virtual work of the pair), so it dissipates (eta / mu) v_rel^T M_e v_rel and
  does not brake the frame.  A free beam has no hub frame: refused there (:meth:`flexbeam.fem.beam.FemBeam.from_case`).

``damp`` = [c, eta / mu].  Shares nothing with the modal model's :mod:`flexbeam.model.damping`.
"""

from __future__ import annotations

import math

import numpy as np

from .element import element_chord, gather, inertia_element
from .jit import fem_jit


@fem_jit
def kelvin_voigt(xe, ve, l0, EA, EI, c, fd, Cd):
    """The Kelvin-Voigt force c B^T D B z_e' of one element into ``fd`` (6), its velocity tangent into ``Cd`` (6 x 6);
    returns the dissipated power z_e'^T c B^T D B z_e'."""
    _, _, ell, cs, sn, _, _ = element_chord(xe)
    r = (-cs, -sn, 0.0, cs, sn, 0.0)
    zz = (sn, -cs, 0.0, -sn, cs, 0.0)
    b1 = np.empty(6)
    b2 = np.empty(6)
    for a in range(6):
        b1[a] = -zz[a] / ell + (1.0 if a == 2 else 0.0)
        b2[a] = -zz[a] / ell + (1.0 if a == 5 else 0.0)
    ud = 0.0
    t1d = 0.0
    t2d = 0.0
    for a in range(6):
        ud += r[a] * ve[a]
        t1d += b1[a] * ve[a]
        t2d += b2[a] * ve[a]
    ka, k = c * EA / l0, c * EI / l0
    N = ka * ud
    M1 = k * (4.0 * t1d + 2.0 * t2d)
    M2 = k * (2.0 * t1d + 4.0 * t2d)
    for a in range(6):
        fd[a] = r[a] * N + b1[a] * M1 + b2[a] * M2
        for b in range(6):
            Cd[a, b] = ka * r[a] * r[b] + k * (
                4.0 * b1[a] * b1[b] + 2.0 * (b1[a] * b2[b] + b2[a] * b1[b]) + 4.0 * b2[a] * b2[b]
            )
    return N * ud + M1 * t1d + M2 * t2d


@fem_jit
def viscous(xe, ve, thd, free, eta_mu, Me, fv):
    """The viscous force (eta / mu) M_e (z_e' - theta' w_e) of one element into ``fv`` (6); returns its power
    (eta / mu) v_rel^T M_e v_rel (``free``: no frame, v_rel = z_e')."""
    rel = np.empty(6)
    for a in range(6):
        rel[a] = ve[a]
    if not free:
        for i in range(2):
            rel[3 * i] += thd * xe[3 * i + 1]
            rel[3 * i + 1] -= thd * xe[3 * i]
            rel[3 * i + 2] -= thd
    power = 0.0
    for a in range(6):
        acc = 0.0
        for b in range(6):
            acc += Me[a, b] * rel[b]
        fv[a] = eta_mu * acc
        power += rel[a] * fv[a]
    return power


@fem_jit
def damping_power(X, V, thd, free, l0, EA, EI, damp, mu, gxi, gw):
    """The power the structural damping dissipates at a state (node arrays X, V: (N + 1) x 3), for the energy
    balance; ``damp`` = [c, eta / mu]."""
    xe = np.empty(6)
    ve = np.empty(6)
    ae = np.zeros(6)
    fd = np.empty(6)
    Cd = np.empty((6, 6))
    fin = np.empty(6)
    Me = np.empty((6, 6))
    fg = np.empty(6)
    G = np.empty((2, 6))
    field = np.zeros(2)
    total = 0.0
    rest = np.zeros_like(X)  # no accelerations: ae stays 0 (gather's third array)
    for e in range(l0.size):
        gather(X, V, rest, e, xe, ve, ae)
        if damp[0] > 0.0:
            total += kelvin_voigt(xe, ve, l0[e], EA, EI, damp[0], fd, Cd)
        if damp[1] > 0.0:
            inertia_element(xe, ve, ae, l0[e], mu, field, gxi, gw, fin, Me, fg, G)
            total += viscous(xe, ve, thd, free, damp[1], Me, fd)
    return total if math.isfinite(total) else math.nan
