"""The one link from a :class:`~flexbeam.results.solution.Solution` to its views (the pattern of xarray's
``DataArray.plot``): ``sol.plot(...)``, ``sol.animate(...)`` and the notebook display call the view modules through
:class:`SolutionViews`, which this module registers on the class when flexbeam is imported.  The results layer
never imports a view; the views are imported only when a figure is asked for.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..results.solution import Solution

FIGURES = ("contact_force", "normal_velocity", "tip_deflection", "friction")


class SolutionViews:
    """The views of one run: ``sol.plot(name, path)`` draws a figure to a file (``name`` in :data:`FIGURES`),
    ``sol.plot.contact_force(path)`` the same by name; ``animate`` and ``html`` serve :meth:`Solution.animate` and
    the notebook display."""

    def __init__(self, sol: Solution) -> None:
        self.sol = sol

    def __call__(self, name: str = "contact_force", path: str | Path | None = None, **options: Any) -> Path:
        if name not in FIGURES:
            raise ValueError(f"plot: unknown figure '{name}'; allowed: {', '.join(FIGURES)}")
        return getattr(self, name)(path, **options)

    def _path(self, path: str | Path | None, name: str) -> Path:
        return Path(path) if path is not None else Path(f"{name}.png")

    def contact_force(self, path: str | Path | None = None, **options: Any) -> Path:
        """The contact force against time (:func:`flexbeam.views.plotting.plot_contact_force`)."""
        from .plotting import plot_contact_force

        return plot_contact_force([self.sol], self._path(path, "contact_force"), **options)

    def normal_velocity(self, path: str | Path | None = None, **options: Any) -> Path:
        """The contact point's normal velocity (:func:`flexbeam.views.plotting.plot_normal_velocity`)."""
        from .plotting import plot_normal_velocity

        return plot_normal_velocity([self.sol], self._path(path, "normal_velocity"), **options)

    def tip_deflection(self, path: str | Path | None = None, **options: Any) -> Path:
        """The tip deflection in the rotating frame (:func:`flexbeam.views.plotting.plot_tip_deflection`)."""
        from .plotting import plot_tip_deflection

        return plot_tip_deflection([self.sol], self._path(path, "tip_deflection"), **options)

    def friction(self, path: str | Path | None = None, **options: Any) -> Path:
        """Coulomb friction's tangential force and slip velocity per pair
        (:func:`flexbeam.views.friction.plot_friction`, a CCFM run with ``contact.friction``)."""
        from .friction import plot_friction

        return plot_friction(self.sol, self._path(path, "friction"), **options)

    def animate(self, path: str | Path, **options: Any) -> Path:
        """An animation of the run (:func:`flexbeam.views.animation.animate`)."""
        from .animation import animate

        return animate(self.sol, path, **options)

    def html(self) -> str:
        """The notebook display (:func:`flexbeam.views.display.solution_html`)."""
        from .display import solution_html

        return solution_html(self.sol)


def register() -> None:
    """Make :class:`SolutionViews` the views of every :class:`Solution`."""
    Solution.views = SolutionViews


register()

__all__ = ["FIGURES", "SolutionViews", "register"]
