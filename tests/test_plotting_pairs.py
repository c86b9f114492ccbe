"""Force figures of runs with several contact pairs: one line per pair that touches, labelled by its obstacle;
single-pair runs drawn as before."""

from __future__ import annotations

import pytest

import flexbeam as fb
from flexbeam.views import plotting
from flexbeam.views.display import solution_html


@pytest.fixture(scope="module")
def two_stops():
    """Both stops touched within 0.1 s (the upper one at about 77 ms), few modes for speed."""
    sol = fb.simulate(fb.load_case("two-stops", {"model.modes": 4, "solver.t_end": 0.1}), "ccfm")
    assert {ev.pair for ev in sol.contacts} == {0, 1}
    return sol


@pytest.fixture(scope="module")
def seed_run():
    return fb.simulate(fb.load_case("seed-experiment", {"model.modes": 2, "solver.t_end": 2e-3}), "ccfm")


@pytest.fixture
def figures(monkeypatch):
    """The figures plot_* would write, kept open instead of saved."""
    kept = []

    def keep(fig, path):
        kept.append(fig)
        return path

    monkeypatch.setattr(plotting, "save_figure", keep)
    yield kept
    for fig in kept:
        plotting.pyplot().close(fig)


def _lines(fig) -> list[tuple[str, object]]:
    ax = fig.axes[0]
    return [(line.get_label(), line.get_color()) for line in ax.get_lines()]


def test_pair_forces_of_two_stops_name_each_pair(two_stops):
    pairs = plotting.pair_forces(two_stops)
    assert [(k, label) for k, label, _ in pairs] == [(0, "obstacle"), (1, "obstacles[0]")]
    assert all(force.max() > 0 for _, _, force in pairs)


def test_single_pair_runs_have_no_pair_lines(seed_run):
    assert plotting.pair_forces(seed_run) is None
    spin = fb.simulate(fb.load_case("spinning-stop", {"model.modes": 2, "solver.t_end": 0.01}), "ccfm")
    assert "pair_contact_force" in spin.arrays and plotting.pair_forces(spin) is None  # one (anywhere) pair


def test_two_stops_force_plot_has_one_line_per_pair_in_contact(two_stops, figures, tmp_path):
    plotting.plot_contact_force([two_stops], tmp_path / "f.png")
    (fig,) = figures
    lines = _lines(fig)
    assert [label for label, _ in lines] == ["flexbeam CCFM, obstacle", "flexbeam CCFM, obstacles[0]"]
    assert len({colour for _, colour in lines}) == 2
    # the window reaches past the upper stop's first contact
    t_up = next(ev.onset for ev in two_stops.contacts if ev.pair == 1) - two_stops.contacts[0].onset
    assert fig.axes[0].get_lines()[1].get_xdata().max() > t_up * 1e3
    assert [t.get_text() for t in fig.axes[0].get_legend().get_texts()] == [label for label, _ in lines]


def test_single_pair_force_plot_is_as_before(seed_run, figures, tmp_path):
    plotting.plot_contact_force([seed_run], tmp_path / "f.png")
    (fig,) = figures
    assert _lines(fig) == [("flexbeam CCFM", "C0")]


def test_solution_html_plots_each_pair(two_stops, seed_run):
    assert "contact force of each contact pair" in solution_html(two_stops)
    assert "contact force of the first contact" in solution_html(seed_run)


def test_two_stops_velocity_plot_has_one_line_per_pair_in_contact(two_stops, seed_run, figures, tmp_path):
    plotting.plot_normal_velocity([two_stops], tmp_path / "v.png")
    plotting.plot_normal_velocity([seed_run], tmp_path / "v1.png")
    pairs, single = figures
    labels = [label for label, _ in _lines(pairs) if label.startswith("flexbeam")]
    assert labels == ["flexbeam CCFM, obstacle", "flexbeam CCFM, obstacles[0]"]
    assert [label for label, _ in _lines(single) if label.startswith("flexbeam")] == ["flexbeam CCFM"]


@pytest.mark.parametrize(
    ("case", "method", "says"),
    [
        ("seed-experiment", "imm", "IMM: instantaneous impacts"),
        ("kane-spinup", "ccfm", "no contact in this run"),
        ("seed-experiment", "ccfm", None),
    ],
)
def test_a_contact_force_figure_with_no_force_says_why(figures, case, method, says):
    """``run --out`` wrote an empty contact_force.png for IMM's impacts and for a run without contact (empty axes,
    'Time after first contact'); it now says why on the axes.  A run with a force history draws it without a note."""
    sol = fb.simulate(fb.load_case(case, {"model.modes": 2, "solver.t_end": 2e-3}), method)
    assert bool(sol.contacts) == (case != "kane-spinup")
    plotting.plot_contact_force([sol], "unused.png")
    (ax,) = figures[-1].axes
    texts = [t.get_text() for t in ax.texts]
    if says is None:
        assert texts == [] and ax.get_xlabel() == "Time after first contact [ms]"
    else:
        assert len(texts) == 1 and texts[0].startswith(says), texts
    if case == "kane-spinup":
        assert ax.get_xlabel() == "Time [ms]"
