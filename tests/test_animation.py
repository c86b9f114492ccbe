"""Animations: the beam's shape against the compiled kinematics and closed forms, the frame plan, the rendered
files (frame count, pixel size, fallback) and the command line."""

from __future__ import annotations

import math
import sys

import matplotlib as mpl
import numpy as np
import pytest
from numpy.testing import assert_allclose
from PIL import Image

import flexbeam as fb
from flexbeam.cli import main
from flexbeam.errors import ModelError
from flexbeam.model.system import BeamSystem
from flexbeam.views.animation import History, Scene, VideoFallbackWarning, animate, auto_scale, beam_shape, frame_times

SMALL = {"model.modes": 2, "solver.t_end": 2e-3}
CLI_SMALL = ["--set", "model.modes=2", "--set", "solver.t_end=0.002", "--frames", "10", "--size", "160x120"]


@pytest.fixture(scope="module")
def small_run():
    case = fb.load_case("seed-experiment", SMALL)
    return case, fb.simulate(case, "ccfm")


def frames_and_size(path) -> tuple[int, tuple[int, int], int]:
    with Image.open(path) as im:
        return im.n_frames, im.size, im.info.get("duration", 0)


# --------------------------------------------------------------------------------------------- beam_shape
def _frame_angle(system: BeamSystem, phi: float, q: np.ndarray) -> float:
    return phi - float(system.beam.d @ q)


@pytest.mark.parametrize("frame", ["system", "hub"])
@pytest.mark.parametrize("coupling", ["first-order", "zeroth-order"])
def test_beam_shape_is_the_kernels_tip_and_contact_point(frame, coupling):
    """At the tip (centre line) and at P (the surface, offset c below the centre line along the section's normal)
    the shape is the compiled kinematics' position, for deflections far beyond the physical ones (so the
    coupling term -1/2 q^T H q counts) and a hub of finite radius.

    Both evaluate r = A(theta) rho with H(x) by Gauss-Legendre quadrature (the kernel over [0, x] at once, beam_shape
    over sub-intervals), which agree to round-off: |r| ~ 1 m, so 1e-12 m is a 10^3 margin over double precision."""
    case = fb.load_case(
        "seed-experiment",
        {"model.modes": 4, "model.frame": frame, "model.coupling": coupling, "hub.radius": 0.05, "hub.inertia": 0.01},
    )
    system = BeamSystem.from_case(case)
    rng = np.random.default_rng(1)
    L, xP, c = system.beam.length, system.contact.position, system.contact.offset
    for _ in range(5):
        phi = rng.uniform(-math.pi, math.pi)
        q = rng.normal(scale=0.02, size=system.n)  # tip deflections of ~1-3 cm: q^T H q / L ~ 1e-3
        th = _frame_angle(system, phi, q)
        y = system.state(th, 0.0, q, np.zeros(system.n))
        X, Y = beam_shape(system, phi, q, [L, xP])
        assert_allclose([X[0], Y[0]], system.point_state(0.0, y, 1)[0], rtol=0, atol=1e-12)
        slope = float(system.beam.shapes(np.array([xP]), 1)[0] @ q)  # the section turns by Psi'(x_P) q
        normal = np.array([math.sin(th + slope), -math.cos(th + slope)])  # A(theta) (sin a, -cos a)
        surface = np.array([X[1], Y[1]]) + c * normal
        assert_allclose(surface, system.point_state(0.0, y, 0)[0], rtol=0, atol=1e-12)
        # the kernel's P is the surface point, c from the centre line (c = 14.5 mm: the offset is no round-off)
        assert_allclose(np.linalg.norm(system.point_state(0.0, y, 0)[0] - [X[1], Y[1]]), c, rtol=1e-12)


@pytest.mark.parametrize("frame", ["system", "hub"])
def test_beam_shape_of_the_undeformed_beam_is_the_hubs_radial_line(frame):
    """q = 0: r(x) = (r_h + x) (cos phi, sin phi), exactly, with the shapes vectorised over times."""
    case = fb.load_case(
        "seed-experiment", {"model.modes": 3, "model.frame": frame, "hub.radius": 0.05, "hub.inertia": 0.01}
    )
    system = BeamSystem.from_case(case)
    x = np.linspace(0.0, system.beam.length, 7)
    phi = np.array([0.0, 0.3, -2.0])
    X, Y = beam_shape(system, phi, np.zeros((3, system.n)), x)
    assert X.shape == (3, 7)
    assert_allclose(X, (0.05 + x) * np.cos(phi)[:, None], rtol=0, atol=1e-15)
    assert_allclose(Y, (0.05 + x) * np.sin(phi)[:, None], rtol=0, atol=1e-15)


def test_beam_shape_keeps_the_beam_inextensible():
    """The coupling deformation u_x = -1/2 int_0^x w'^2 makes the centre line inextensible to second order
    (hub frame, hub of zero radius): d(x + u_x)/dx = 1 - w'^2/2, so its arc length is exactly
    int sqrt(1 + w'^4/4) dx -- 1.9e-4 m over L for slopes up to 0.33, where dropping the coupling term would give
    int w'^2/2 = 9.3e-3 m.  The chord sum over 4001 points is short of the arc by 5.7e-10 m (measured; it falls
    as h^2): 1e-8 m is a 17x margin."""
    case = fb.load_case("seed-experiment", {"model.modes": 3, "model.frame": "hub"})
    system = BeamSystem.from_case(case)
    L = system.beam.length
    q = np.array([0.02, -0.01, 0.005])
    x = np.linspace(0.0, L, 4001)
    X, Y = beam_shape(system, 0.4, q, x)
    arc = float(np.sum(np.hypot(np.diff(X), np.diff(Y))))
    slope = system.beam.shapes(x, 1) @ q
    assert_allclose(arc - L, np.trapezoid(np.sqrt(1.0 + slope**4 / 4.0) - 1.0, x), rtol=0, atol=1e-8)
    assert np.trapezoid(slope**2 / 2.0, x) > 1e-3 * L


# ------------------------------------------------------------------------------------------------- frames
def test_frame_times_uniform_without_contacts():
    t, density = frame_times((0.0, 2.0), [], 11)
    assert_allclose(t, np.linspace(0.0, 2.0, 11), rtol=0, atol=1e-15)
    assert_allclose(density, 5.0)


def test_frame_times_put_the_share_of_frames_into_the_contacts():
    """One contact of 1 ms in a 100 ms window, half of 201 frames to it (widened by 25 % either side): 100 frame
    intervals in 1.5 ms, 100 in 98.5 ms; the first and last frames at the window's ends."""
    t, density = frame_times((0.0, 0.1), [(0.02, 0.021)], 201, contact_share=0.5, pad=0.25)
    assert t[0] == 0.0 and t[-1] == 0.1 and np.all(np.diff(t) > 0)
    inside = np.count_nonzero((t >= 0.02 - 0.25e-3 - 1e-12) & (t <= 0.021 + 0.25e-3 + 1e-12))
    assert inside in (100, 101, 102)  # 100 intervals: 100 or 101 frames, one more if a frame sits on both edges
    assert_allclose(density.max(), 100 / 1.5e-3, rtol=1e-9)
    assert_allclose(density.min(), 100 / 98.5e-3, rtol=1e-9)


def test_frame_times_uniform_when_contacts_fill_the_window():
    """A resting contact over most of the window: contacts no denser than free flight, frames uniform."""
    t, _ = frame_times((0.0, 1.0), [(0.0, math.nan)], 5)
    assert_allclose(t, np.linspace(0.0, 1.0, 5))


@pytest.mark.parametrize("deflection", [1e-9, 3.3e-7, 1e-6, 4.7e-5, 1e-3, 0.0123])
def test_auto_scale_draws_the_largest_deflection_at_11_to_12_percent(deflection):
    k = auto_scale(deflection, 0.7)
    assert 0.109 <= k * deflection / 0.7 <= 0.12 * (1 + 1e-12)  # k = 0.12 L / d exactly when it has 2 digits
    assert auto_scale(0.5, 0.7) == 1.0  # never shrinks a deflection


def test_scene_magnifies_about_the_line_through_P_and_P_stays_on_the_obstacle(small_run):
    """The auto scale draws the largest deflection from the reference line O-P at 10-15 % of L; the magnified
    contact point stays where the true one is, so in contact it touches the sphere (the true gap is micrometres;
    1 mm = 1.4e-3 L is 10x over the distance round-off and the band's tangential shift can add), while with the
    hub's radial line as reference it is displaced by the magnified deflection at P."""
    case, sol = small_run
    history = History.load(sol)
    scene = Scene.build(history, None, 30, 0.5, "contact", "auto")
    L = case.beam.length
    e1 = scene.chord[:, 1, :] / np.linalg.norm(scene.chord[:, 1, :], axis=1, keepdims=True)
    off_line = np.abs(e1[:, None, 0] * scene.centre[..., 1] - e1[:, None, 1] * scene.centre[..., 0])
    assert 0.10 <= off_line.max() / L <= 0.15
    ob = scene.system.contact.obstacle
    touching = scene.force > 0
    assert touching.sum() >= 5
    dist = np.linalg.norm(scene.contact_point[touching] - ob.centre, axis=1) - ob.radius
    assert np.max(np.abs(dist)) < 1e-3
    hub = Scene.build(history, None, 30, 0.5, "hub", scene.scale)
    dist_hub = np.linalg.norm(hub.contact_point[touching] - ob.centre, axis=1) - ob.radius
    assert np.max(np.abs(dist_hub)) > 5e-3


# ----------------------------------------------------------------------------------------------- rendering
def test_gif_has_the_frames_and_size_asked(small_run, tmp_path):
    _, sol = small_run
    font = mpl.rcParams["font.size"]
    path = sol.animate(tmp_path / "beam.gif", frames=10, size=(160, 120), fps=20, progress=False)
    assert path == tmp_path / "beam.gif"
    assert frames_and_size(path) == (10, (160, 120), 50)
    assert mpl.rcParams["font.size"] == font  # no rc state leaks
    assert [p.name for p in tmp_path.iterdir()] == ["beam.gif"]  # the temporary file is gone


def test_progress_is_reported_per_frame(small_run, tmp_path):
    _, sol = small_run
    calls = []
    animate(sol, tmp_path / "a.gif", frames=6, size=(96, 64), progress=lambda done, total: calls.append((done, total)))
    assert calls == [(i, 6) for i in range(1, 7)]


def test_mp4_falls_back_to_gif_without_imageio_ffmpeg(small_run, tmp_path, monkeypatch):
    _, sol = small_run
    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)  # import imageio_ffmpeg now raises ImportError
    with pytest.warns(VideoFallbackWarning, match="imageio-ffmpeg"):
        path = animate(sol, tmp_path / "beam.mp4", frames=8, size=(160, 120), progress=False)
    assert path == tmp_path / "beam.gif" and not (tmp_path / "beam.mp4").exists()
    assert frames_and_size(path)[:2] == (8, (160, 120))


def test_mp4_has_the_frames_and_size_asked(small_run, tmp_path):
    ffmpeg = pytest.importorskip("imageio_ffmpeg")
    _, sol = small_run
    path = animate(sol, tmp_path / "beam.mp4", frames=12, size=(160, 120), progress=False)
    assert path.suffix == ".mp4"
    assert ffmpeg.count_frames_and_secs(str(path))[0] == 12
    reader = ffmpeg.read_frames(str(path))
    meta = next(reader)
    reader.close()
    assert tuple(meta["size"]) == (160, 120)


def test_a_result_without_modal_coordinates_is_refused(small_run, tmp_path):
    """A finite-element result stores q with no modes; so does this dataset cut down to none."""
    _, sol = small_run
    ds = sol.to_xarray().isel(mode=slice(0, 0))
    with pytest.raises(ModelError, match="modal coordinates"):
        animate(ds, tmp_path / "x.gif", frames=4, size=(64, 64), progress=False)


# --------------------------------------------------------------------------------------------- command line
def test_cli_from_a_case(tmp_path, capsys):
    out = tmp_path / "beam.gif"
    main(["animate", "seed-experiment", *CLI_SMALL, "--out", str(out)])
    assert frames_and_size(out)[:2] == (10, (160, 120))
    assert capsys.readouterr().out.strip() == f"wrote {out}"


def test_cli_from_a_result_file(small_run, tmp_path):
    _, sol = small_run
    nc = sol.to_netcdf(tmp_path / "result.nc")
    out = tmp_path / "beam.gif"
    main(
        [
            "animate",
            str(nc),
            "--out",
            str(out),
            "--frames",
            "7",
            "--size",
            "120x90",
            "--window",
            "0,1e-3",
            "--scale",
            "500",
        ]
    )
    assert frames_and_size(out)[:2] == (7, (120, 90))


def test_cli_mp4_falls_back_with_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)
    main(["animate", "seed-experiment", *CLI_SMALL, "--out", str(tmp_path / "beam.mp4")])
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("note: imageio-ffmpeg is not installed")
    assert frames_and_size(tmp_path / "beam.gif")[:2] == (10, (160, 120))


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["no-such-case", "--out", "x.gif"], "case"),
        (["missing.nc", "--out", "x.gif"], "missing.nc"),
        (["seed-experiment", *CLI_SMALL, "--out", "x.avi"], ".avi"),
        (["seed-experiment", *CLI_SMALL, "--out", "x.gif", "--window", "1e-3"], "--window"),
        (["seed-experiment", *CLI_SMALL, "--out", "x.gif", "--window", "1e-3,5e-4"], "window"),
        (["seed-experiment", *CLI_SMALL, "--out", "x.gif", "--window", "0,1"], "window"),
        (["seed-experiment", *CLI_SMALL, "--out", "x.gif", "--scale", "big"], "--scale"),
        (["seed-experiment", *CLI_SMALL, "--out", "x.gif", "--scale", "-3"], "scale"),
        (["seed-experiment", *CLI_SMALL, "--out", "x.gif", "--size", "10x10"], "size"),
        (["seed-experiment", *CLI_SMALL, "--out", "x.gif", "--frames", "1"], "frames"),
        (["result.nc", "--out", "x.gif", "--method", "imm"], "--method"),  # (ignored before: the file holds its run)
    ],
)
def test_cli_bad_input_is_one_line_exit_2(args, field, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    if args[0] == "result.nc":
        (tmp_path / "result.nc").write_bytes(b"")
    with pytest.raises(SystemExit) as exc:
        main(["animate", *args])
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and field in err[0] and "Traceback" not in err[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == (["result.nc"] if args[0] == "result.nc" else [])


def test_cli_a_run_that_ends_early_is_animated_and_reported(tmp_path, capsys):
    """IMM on the rod's end stops at solver.max_contacts: ``animate`` drew what was run and exited 0 in silence,
    where ``run`` reports it; now the same line as ``run``'s and exit 1, the file written."""
    out = tmp_path / "rod.gif"
    with pytest.raises(SystemExit) as exc:
        main(["animate", "rod-end", "-m", "imm", "-s", "solver.max_contacts=20", "--frames", "4", "--size", "64x48",
              "--out", str(out)])  # fmt: skip
    assert exc.value.code == 1 and out.is_file()
    captured = capsys.readouterr()
    assert captured.out.strip() == f"wrote {out}"
    err = captured.err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("imm: run ended early with status 'max-contacts'"), err


# --------------------------------------------------------------------------------- several contact pairs
TWO_STOPS = {"model.modes": 4, "solver.t_end": 0.02, "initial.impact_velocity": -1.5}


@pytest.fixture(scope="module")
def two_stops_run():
    """The beam between two stops, fast enough to hit both within 20 ms."""
    sol = fb.simulate(fb.load_case("two-stops", TWO_STOPS), "ccfm")
    assert {ev.pair for ev in sol.contacts} == {0, 1}
    return sol


def test_two_stops_animation_draws_every_obstacle_and_each_pairs_force(two_stops_run, tmp_path):
    """Every obstacle is drawn (one artist each), each pair has its contact point and its force at the frames
    (the first pair's is ``force``), and the GIF has the frames asked."""
    from flexbeam.views.animation import FrameRenderer

    sol = two_stops_run
    scene = Scene.build(History.load(sol), None, 8, 0.5, "contact", "auto")
    assert scene.pairs == 2
    assert scene.pair_points.shape == (8, 2, 2) and scene.pair_force.shape == (8, 2)
    assert_allclose(scene.pair_force[:, 0], scene.force)
    assert_allclose(scene.pair_points[:, 0], scene.contact_point)
    assert scene.pair_points[0, 1, 1] > scene.pair_points[0, 0, 1]  # the upper pair's point is above P
    renderer = FrameRenderer(scene, 160, 120, 25.0)
    assert len(renderer.obstacles) == len(scene.system.contact.obstacles) == 2
    assert renderer.render(3).shape == (120, 160, 4)
    path = animate(sol, tmp_path / "two.gif", frames=7, size=(160, 120), progress=False)
    assert frames_and_size(path)[:2] == (7, (160, 120))


def test_history_of_a_dataset_keeps_the_pair_arrays(two_stops_run):
    sol = two_stops_run
    history = History.from_dataset(sol.to_xarray())
    assert_allclose(history.pair_force, sol["pair_contact_force"])
    assert_allclose(history.pair_position, sol["pair_contact_position"])


def test_single_pair_scene_has_one_pair(small_run):
    _, sol = small_run
    scene = Scene.build(History.load(sol), None, 6, 0.5, "contact", "auto")
    assert History.load(sol).pair_force is None
    assert scene.pairs == 1 and scene.pair_points.shape == (6, 1, 2)
    assert_allclose(scene.pair_force[:, 0], scene.force)


def test_anywhere_contact_point_is_on_the_side_facing_the_obstacle():
    """spinning-stop: the beam sweeps into the sphere with its upper side; drawn at true scale, the marked
    contact point (the result's moving pair_contact_position) lies on the sphere while in contact."""
    case = fb.load_case("spinning-stop", {"model.modes": 4, "solver.t_end": 0.45})
    sol = fb.simulate(case, "ccfm")
    scene = Scene.build(History.load(sol), (0.44, 0.45), 12, 0.5, "contact", 1.0)
    ob = scene.system.contact.obstacle
    touching = scene.pair_force[:, 0] > 0
    assert touching.any()
    dist = np.linalg.norm(scene.pair_points[touching, 0] - ob.centre, axis=1) - ob.radius
    assert np.max(np.abs(dist)) < 1e-3


# ------------------------------------------------------------------------------------------------ a free beam
@pytest.fixture(scope="module")
def bar_drop_run():
    from pathlib import Path

    case = fb.load_case(str(Path(__file__).parent / "validation" / "data" / "free-bar-drop.toml"), {"model.modes": 4})
    return fb.simulate(case, "ccfm")


def test_beam_shape_of_a_free_beam_is_the_kernels_tip():
    """A free bar (4 modes) at random frame origins R, angles and large deflections (tip ~1 cm on 20 cm: the
    foreshortening counts): beam_shape's tip with ``origin`` = R is the compiled kinematics' tip point, whose
    foreshortening starts from -H_bar (docs/free-beam.md); 1e-12 m as for the joint (round-off of |r| ~ 1 m)."""
    from pathlib import Path

    case = fb.load_case(str(Path(__file__).parent / "validation" / "data" / "free-bar-drop.toml"), {"model.modes": 4})
    system = BeamSystem.from_case(case)
    rng = np.random.default_rng(2)
    L = system.beam.length
    for _ in range(5):
        R, th = rng.uniform(-1.0, 1.0, 2), rng.uniform(-math.pi, math.pi)
        q = rng.normal(scale=0.003, size=system.n)
        y = system.joint.state(system.n, np.array([R[0], R[1], th]), np.zeros(3), q, np.zeros(system.n), [0.0, 0.0])
        X, Y = beam_shape(system, th, q, [L], origin=R)
        assert_allclose([X[0], Y[0]], system.point_state(0.0, y, 1)[0], rtol=0, atol=1e-12)
        assert abs(float(system.beam.shapes(np.array([L]), 0)[0] @ q)) > 1e-3  # a deflection that counts
    # one origin for several frames (shape (2,)) is every frame's
    phis, qs = np.array([0.1, -0.7]), np.zeros((2, system.n))
    X, Y = beam_shape(system, phis, qs, [0.0, L], origin=R)
    assert_allclose(X, R[0] + (np.array([0.0, L]) - 0.5 * L) * np.cos(phis)[:, None], rtol=0, atol=1e-15)
    assert_allclose(Y, R[1] + (np.array([0.0, L]) - 0.5 * L) * np.sin(phis)[:, None], rtol=0, atol=1e-15)


def test_a_free_beams_scene_is_its_outline_about_g(bar_drop_run):
    """Drawn at true scale (scale 1) the free bar's band is the outline the clearance check computes at the same
    state (flexbeam.model.clearance.outline: the frame origin R = G plus A(theta) rho(x), its own quadrature of the
    foreshortening; the band's normal from the line's differences: 1e-6 m, the station spacing's slope error times
    c; measured 1.9e-8), the chord runs end to end through G along the frame's axis, and the dataset's history draws
    the same."""
    from flexbeam.model.clearance import outline

    sol = bar_drop_run
    history = History.load(sol)
    scene = Scene.build(history, None, 6, 0.5, "contact", 1.0)
    system = scene.system
    L = system.beam.length
    i = 3
    t = scene.times[i]
    R = scene.origin[i]
    e1 = (scene.chord[i, 1] - scene.chord[i, 0]) / L
    assert_allclose(np.linalg.norm(scene.chord[i, 1] - scene.chord[i, 0]), L, rtol=1e-12)
    assert_allclose(0.5 * (scene.chord[i, 0] + scene.chord[i, 1]), R, rtol=0, atol=1e-12)
    theta = float(np.interp(t, sol.time, sol["theta"]))
    assert_allclose(e1, [math.cos(theta), math.sin(theta)], rtol=0, atol=1e-12)
    q = np.array([np.interp(t, sol.time, c) for c in sol["q"].T])[: system.beam.n]
    xs, lower, upper = outline(system.beam, abs(system.case.beam.surface_offset), theta, q, tuple(R))
    x = np.union1d(np.linspace(0.0, L, 121), [p.position for p in system.contact.pairs])
    for edge, ref in ((scene.lower[i], lower), (scene.upper[i], upper)):
        drawn = np.column_stack([np.interp(xs, x, edge[:, k]) for k in range(2)])
        assert_allclose(drawn, ref, rtol=0, atol=1e-6)
    again = Scene.build(History.from_dataset(sol.to_xarray()), None, 6, 0.5, "contact", 1.0)
    assert_allclose(again.centre, scene.centre, rtol=0, atol=1e-12)


def test_a_free_beam_is_animated(bar_drop_run, tmp_path):
    """The bar drop renders (a GIF of the frames and size asked), G marked where the frames put it."""
    from flexbeam.views.animation import FrameRenderer

    scene = Scene.build(History.load(bar_drop_run), None, 5, 0.5, "contact", "auto")
    renderer = FrameRenderer(scene, 160, 120, 25.0)
    renderer.update(2)
    assert_allclose(renderer._beam.hub.center, scene.origin[2])
    path = animate(bar_drop_run, tmp_path / "drop.gif", frames=5, size=(160, 120), progress=False)
    assert frames_and_size(path)[:2] == (5, (160, 120))


def test_auto_scale_does_not_magnify_round_off():
    """A beam that does not bend (the rod of ``rod-end``: its bending 2e-19 m, round-off of positions of order L)
    was drawn bent and tilted into the plane at x1.2e17; a deflection within 1e3 eps L is drawn as it is."""
    assert auto_scale(2e-19, 1.0) == 1.0 and auto_scale(1e-13, 0.7) == 1.0
    assert auto_scale(1e-9, 0.7) > 1e7  # a nanometre on a 0.7 m beam is still a shape
