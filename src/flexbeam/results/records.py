"""The records of a run: the output variables' names and units, and one contact's record.

:class:`ContactEvent` is what the impact methods (and the finite-element reference) log for every located contact;
:data:`VARIABLES` names the arrays a :class:`~flexbeam.results.solution.Solution` holds, with their units.
"""

from __future__ import annotations

from dataclasses import dataclass

#: variable name -> (units, long name)
VARIABLES: dict[str, tuple[str, str]] = {
    "theta": ("rad", "Hub angle"),
    "theta_rate": ("rad/s", "Hub angular velocity"),
    # the mode shapes are dimensionless (int phi^2 dx = L, model/modes.py, model/axial.py): w = sum phi_i q_i, q in m
    "q": ("m", "Modal coordinate"),
    "q_rate": ("m/s", "Modal velocity"),
    "contact_force": ("N", "Contact force"),
    "gap": ("m", "Gap at the contact point"),
    "normal_velocity": ("m/s", "Normal velocity of the contact point"),
    "measuring_velocity": ("m/s", "Normal velocity of the measuring points"),
    "kinetic_energy": ("J", "Kinetic energy"),
    "elastic_energy": ("J", "Elastic energy"),
    "gravitational_energy": ("J", "Gravitational energy"),
    "contact_energy": ("J", "Contact potential energy"),
    "dissipated_energy": ("J", "Energy dissipated by contact (and the support's dashpot)"),
    # W of docs/formulation.md: the drive's work, the moving base's (W_b) and a moving ground obstacle's (W_g)
    "drive_work": ("J", "Work done on the beam: joint torque or prescribed drive, moving base, moving ground obstacle"),
    "total_energy": ("J", "Total energy T + V_e + V_g + U_c + E_d - W (W: drive_work), conserved by the equations"),
    "joint_torque": ("N m", "Joint torque"),
    "tip_deflection": ("m", "Tip deflection in the rotating frame"),
    "support_displacement": ("m", "Displacement s of the compliant obstacle along its support axis"),
    "sensor_force": ("N", "Force read under the compliant obstacle support, -(k_s s + c_s s')"),
    "pair_gap": ("m", "Gap of each contact pair"),
    "pair_normal_velocity": ("m/s", "Normal velocity of each contact pair's point"),
    "pair_contact_force": ("N", "Contact force of each contact pair"),
    "pair_contact_position": ("m", "Material coordinate x of each contact pair's point (moves for contact anywhere)"),
    "pair_tangential_force": ("N", "Friction force of each contact pair along its tangent t = (-n_y, n_x)"),
    "pair_slip_velocity": ("m/s", "Slip velocity of each contact pair's point along its tangent"),
    "pair_friction_state": ("1", "Friction state of each contact pair: 0 no frictional contact, 1 slip, 2 stick"),
    "centre_of_mass": ("m", "Position (x, y) of the free beam's centre of mass G"),
    "centre_of_mass_velocity": ("m/s", "Velocity (x, y) of the free beam's centre of mass G"),
}
#: variables (time x pair) present only when a case has several contact pairs or a contact anywhere
PAIR_VARIABLES = ("pair_gap", "pair_normal_velocity", "pair_contact_force", "pair_contact_position")
#: variables (time x pair) present only in a frictional run: Coulomb friction (:mod:`flexbeam.methods.coulomb`:
#: CCFM, CCM, IMM's resting contact) and the FE reference's regularised law
FRICTION_VARIABLES = ("pair_tangential_force", "pair_slip_velocity", "pair_friction_state")
#: variables (time x axis) present only for a free beam (``joint.kind = "free"``): G's position and velocity, the
#: coordinates x_G, y_G and their rates (docs/free-beam.md)
CENTRE_VARIABLES = ("centre_of_mass", "centre_of_mass_velocity")


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
    #: the frictional impulse along the contact's tangent t = (-n_y, n_x) [N s] (IMM with friction; NaN without)
    tangential_impulse: float = float("nan")

    @property
    def duration(self) -> float:
        return self.end - self.onset
