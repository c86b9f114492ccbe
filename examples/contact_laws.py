"""
Contact laws compared on the seed case
======================================

CCFM needs a contact force law.  Every law here is a Hertz spring K d^n with
hysteresis damping, F = K d^n (1 + chi d'/d'_0), and differs only in how the
damping factor chi follows from the coefficient of restitution e (here e = 0.8):
Hunt-Crossley (1975), Lankarani-Nikravesh (1990), Flores et al. (2011),
Gonthier et al. (2004) and Carvalho-Martins (2019); Hertz (1882) is the
undamped spring.

Two runs per law:

* the **flexible beam** of the seed experiment (12 modes), whose first contact is
  plotted;
* its **rigid limit** (no modes, no gravity): the rod then meets the hemisphere like a
  single mass m_eff = J_O / x_P^2, for which each law's *effective* restitution has an
  exact answer, the root e_eff of (1 + e_eff) chi = ln[(1 + chi) / (1 - e_eff chi)]
  (Carvalho & Martins 2019), and the Hertz law has Johnson's closed form
  F_max = K d_max^1.5, d_max = (5 m v^2 / 4K)^(2/5), t_c = 2.9433 d_max / v.
"""

# %%
# Simulate the first contact with each law
# ----------------------------------------
import flexbeam as fb

LAWS = ("hertz", "hunt_crossley", "lankarani_nikravesh", "flores", "gonthier", "carvalho_martins")
#: the first contact and its aftermath: 2 ms (the contact lasts ~0.6 ms)
SHORT = {"solver.t_end": 2e-3}

flexible = {law: fb.simulate(fb.load_case("seed-experiment", {**SHORT, "contact.law": law})) for law in LAWS}
rigid = {
    law: fb.simulate(
        fb.load_case("seed-experiment", {**SHORT, "contact.law": law, "model.modes": 0, "model.gravity": 0.0})
    )
    for law in LAWS
}

#: effective restitution of each law in the rigid limit, -v+/v- of the first contact
effective_restitution = {
    law: -sol.metrics()["post_impact_velocity"] / sol.metrics()["impact_velocity"] for law, sol in rigid.items()
}
peak_force = {law: sol.metrics()["peak_force"] for law, sol in flexible.items()}

# %%
# The flexible beam's peak is about half the rigid rod's: in the 0.6 ms of contact only
# the part of the beam near P takes part.  Laws that dissipate more (lower e_eff) give
# lower peaks and longer contacts.
if __name__ == "__main__":
    print(f"{'law':22}{'e_eff (rigid)':>14}{'peak, rigid [N]':>17}{'peak, flexible [N]':>20}")
    for law in LAWS:
        print(
            f"{law:22}{effective_restitution[law]:14.4f}{rigid[law].metrics()['peak_force']:17.1f}"
            f"{peak_force[law]:20.1f}"
        )

# %%
# Force histories of the flexible beam's first contact
# ----------------------------------------------------
if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
    for law, sol in flexible.items():
        t0 = sol.contacts[0].onset
        window = (sol.time >= t0) & (sol.time <= t0 + 0.8e-3)
        ax.plot(
            (sol.time[window] - t0) * 1e3,
            sol["contact_force"][window],
            label=f"{law} (e_eff = {effective_restitution[law]:.3f})",
        )
    ax.set(xlabel="Time after first contact [ms]", ylabel="Contact force [N]", title="Seed case, CCFM, nominal e = 0.8")
    ax.legend(fontsize=8)
    plt.show()
