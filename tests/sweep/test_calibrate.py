"""Calibration recovers known contact parameters from synthetic noisy measurements."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.calibrate import Parameter, covariance, parse_columns, parse_features, read_measured
from flexbeam.errors import ParameterError

TRUE = {"contact.stiffness": 2.0e9, "contact.restitution": 0.6}


def _synthetic_csv(path, case, seed=1, offset=3.7e-4, noise=0.01):
    """Force and velocity of the true case sampled at 1 MHz from 0.1 ms before contact, on a
    shifted clock, with Gaussian noise of ``noise`` x peak force and 5 mm/s."""
    sol = fb.simulate(fb.load_case(case, TRUE))
    t = np.arange(-1e-4, 1.2e-3, 1e-6)
    force = np.interp(t, sol.time, sol["contact_force"], left=0.0)
    velocity = np.interp(t, sol.time, sol["normal_velocity"])
    rng = np.random.default_rng(seed)
    force = force + rng.normal(0.0, noise * force.max(), t.size)
    velocity = velocity + rng.normal(0.0, 5e-3, t.size)
    rows = "\n".join(f"{a:.9g},{b:.9g},{c:.9g}" for a, b, c in zip(t + offset, force, velocity))
    path.write_text("# synthetic measurement\nt,F,v\n" + rows + "\n")
    return sol


def _noise_level(path, truth, offset=3.7e-4, noise=0.01) -> tuple[float, int]:
    """(expected residual sigma, sample count) of a ``_synthetic_csv`` file: the noise put in (``noise`` x the
    true peak) over the largest measured magnitude, by which the residuals are divided."""
    data = np.loadtxt(path, delimiter=",", skiprows=2)
    peak = np.interp(data[:, 0] - offset, truth.time, truth["contact_force"], left=0.0).max()
    return noise * peak / np.max(np.abs(data[:, 1])), data.shape[0]


def test_force_history_recovers_stiffness_and_restitution_from_the_cli(tmp_path):
    """Rigid beam; the fit starts from the Hertz stiffness (4.4e9) and e = 0.8.  The errors are consistent with
    the reported standard uncertainties (within 4 u: a false alarm once in 16 000 for a Gaussian estimate;
    measured 0.68 u and 0.89 u); besides, K within 2 % (measured 0.12 %) with u below 2 % (0.17 %), e within 0.04
    (0.0039) with u below 0.03 (0.0026).  The residual sigma estimates the noise put in with relative sampling
    error 1 / sqrt(2 N): bound 5 of those (measured 0.9)."""
    sets = ["--set", "model.modes=0", "--set", "solver.t_end=2e-3"]
    case = fb.load_case("seed-experiment", {"model.modes": 0, "solver.t_end": 2e-3})
    data = tmp_path / "measured.csv"
    truth = _synthetic_csv(data, case)
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "flexbeam.cli",
            "calibrate",
            "seed-experiment",
            *sets,
            "--data",
            str(data),
            "--columns",
            "time=t,force=F",
            "--fit",
            "contact.stiffness,contact.restitution",
            "--json",
            "--out",
            str(tmp_path / "out"),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert r.returncode == 0, r.stderr
    report = json.loads(r.stdout)
    K, e = report["parameters"]["contact.stiffness"], report["parameters"]["contact.restitution"]
    assert abs(K["value"] - TRUE["contact.stiffness"]) < 4 * K["uncertainty"]
    assert abs(e["value"] - TRUE["contact.restitution"]) < 4 * e["uncertainty"]
    assert K["value"] == pytest.approx(TRUE["contact.stiffness"], rel=0.02) and K["uncertainty"] < 0.02 * K["value"]
    assert e["value"] == pytest.approx(TRUE["contact.restitution"], abs=0.04) and e["uncertainty"] < 0.03
    assert report["data"]["channels"] == ["force"]
    sigma, n = _noise_level(data, truth)
    assert report["residuals"]["sigma"] == pytest.approx(sigma, rel=5 / np.sqrt(2 * n))
    # the fitted shift is what the 10 % threshold's alignment leaves: a fraction of the 0.6 ms contact (measured
    # 1.0e-7 s; the threshold crossing of noisy data moves by ~1e-6 s); the offset itself is checked below
    assert abs(report["data"]["time_shift"]) < 1e-5
    for name in ("calibration.json", "fitted.toml", "overlay.png", "residuals.csv"):
        assert (tmp_path / "out" / name).stat().st_size > 0
    fitted = fb.load_case(tmp_path / "out" / "fitted.toml")
    assert fitted.contact.stiffness == K["value"] and fitted.contact.restitution == e["value"]


def test_features_of_a_two_mode_beam_recover_the_parameters():
    case = fb.load_case("seed-experiment", {"model.modes": 2, "solver.t_end": 0.1})
    m = fb.simulate(fb.load_case(case, TRUE)).metrics()
    features = {k: m[k] for k in ("peak_force", "contact_duration", "post_impact_velocity")}
    fit = fb.calibrate(case, fit=["contact.stiffness", "contact.restitution"], features=features)
    assert fit.success
    assert fit.fitted["contact.stiffness"] == pytest.approx(TRUE["contact.stiffness"], rel=1e-3)
    assert fit.fitted["contact.restitution"] == pytest.approx(TRUE["contact.restitution"], abs=1e-3)
    # the fit simulated only the first contact and its aftermath; the fitted case keeps t_end
    assert fit.solution.time[-1] < 5e-3 and fit.case.solver.t_end == 0.1
    assert fit.to_dict()["features"]["peak_force"]["fitted"] == pytest.approx(m["peak_force"], rel=1e-4)


def test_force_and_velocity_together(tmp_path):
    """Both channels: K and e within 4 u (measured 0.99 u, 0.83 u) and within 2 % and 0.02 (0.17 %, 0.0009); each
    channel's rms residual is its noise, within 5 sampling errors 5 / sqrt(2 N) = 0.098 (measured 0.52 %, 0.44 %).
    The clock offset: model time = data time - t_data + t_model + shift (t_data, t_model: where the force
    first reaches 10 % of the measured peak), so t_data - t_model - shift must be the true 0.37 ms within 4
    standard uncertainties of the shift (measured 0.37 u)."""
    case = fb.load_case("seed-experiment", {"model.modes": 0, "solver.t_end": 2e-3})
    data = tmp_path / "measured.csv"
    truth = _synthetic_csv(data, case, seed=2)
    measured = read_measured(data, {"time": "t", "force": "F", "velocity": "v"})
    fit = fb.calibrate(case, fit="contact.stiffness,contact.restitution", data=measured)
    for (key, value), u in zip(fit.fitted.items(), fit.uncertainty, strict=True):
        assert abs(value - TRUE[key]) < 4 * u, key
    assert fit.fitted["contact.stiffness"] == pytest.approx(TRUE["contact.stiffness"], rel=0.02)
    assert fit.fitted["contact.restitution"] == pytest.approx(TRUE["contact.restitution"], abs=0.02)
    n = int(fit.data_mask.sum())
    assert fit.channel_rms["velocity"] == pytest.approx(5e-3, rel=5 / np.sqrt(2 * n))
    peak = np.interp(measured.time - 3.7e-4, truth.time, truth["contact_force"], left=0.0).max()
    assert fit.channel_rms["force"] == pytest.approx(0.01 * peak, rel=5 / np.sqrt(2 * n))
    t_data = (measured.time[fit.data_mask] - fit.aligned_time)[0]
    offset = t_data - fit.model_reference[1] - fit.time_shift
    assert abs(offset - 3.7e-4) < 4 * fit.time_shift_uncertainty


def test_covariance_is_sigma2_inverse_normal_matrix():
    rng = np.random.default_rng(0)
    x = np.linspace(0.0, 1.0, 40)
    J = np.column_stack([np.ones_like(x), x])
    r = rng.normal(0.0, 0.1, x.size)
    cov, s2, dof = covariance(J, r)
    assert dof == 38 and s2 == pytest.approx(r @ r / 38)
    np.testing.assert_allclose(cov, s2 * np.linalg.inv(J.T @ J), rtol=1e-12)
    singular, _, _ = covariance(np.column_stack([x, 2 * x]), r)
    assert np.all(np.isinf(singular))
    _, s2, dof = covariance(J[:2], r[:2])
    assert dof == 0 and np.isnan(s2)


def test_parameter_scaling_follows_the_field_ranges():
    case = fb.load_case("seed-experiment")
    K = Parameter.of(case, "contact.stiffness")  # case gives none: the Hertz value
    assert K.log and K.x0 == pytest.approx(4.43e9, rel=1e-2) and K.units.startswith("N/m")
    e = Parameter.of(case, "contact.restitution")
    assert not e.log and (e.lower, e.upper) == (0.0, 1.0) and e.bounds() == pytest.approx((-0.8, 0.2))
    assert K.value(np.log(0.5)) == pytest.approx(0.5 * K.x0)


def test_an_obstacles_field_is_fitted_by_its_index():
    """``obstacles[0].contact.stiffness`` as --set and sweep take it (an AttributeError traceback before): two-stops'
    second stop is a sphere like its first (radius 10 mm, E = 68.95 GPa) under the same beam, so its Hertz stiffness
    is the first stop's, ~4.43e9 N/m^1.5 (the seed's, above); a value given is its start."""
    case = fb.load_case("two-stops")
    K = Parameter.of(case, "obstacles[0].contact.stiffness")
    assert K.log and K.x0 == pytest.approx(4.43e9, rel=1e-2) and K.units.startswith("N/m")
    given = Parameter.of(fb.load_case("two-stops", {"obstacles[0].contact.stiffness": 3e9}), K.key)
    assert given.x0 == 3e9
    with pytest.raises(ParameterError, match=r"obstacles\[3\].contact.stiffness: obstacles\[3\] does not exist"):
        Parameter.of(case, "obstacles[3].contact.stiffness")


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: Parameter.of(fb.load_case("seed-experiment"), "model.modes"), "model.modes"),
        (lambda: Parameter.of(fb.load_case("seed-experiment"), "contact.law"), "contact.law"),
        (
            lambda: Parameter.of(fb.load_case("seed-experiment"), "contact.stifness"),
            "contact.stifness: unknown field, did you mean stiffness",
        ),
        (lambda: parse_columns("tim=t"), "best matches: time"),
        (lambda: parse_features("peak_force=abc"), "--features"),
        (lambda: fb.calibrate("seed-experiment", fit=["contact.restitution"]), "--data"),
        (
            lambda: fb.calibrate("seed-experiment", fit=["contact.restitution"], features={"peak_forc": 1.0}),
            "peak_force",
        ),
        # through Python, a feature that is no finite number reached scipy: "Residuals are not finite ..."
        (
            lambda: fb.calibrate("seed-experiment", fit=["contact.restitution"], features={"peak_force": math.nan}),
            "--features peak_force: must be a finite number",
        ),
        (
            lambda: fb.calibrate("seed-experiment", fit=["contact.restitution"], features={"peak_force": True}),
            "--features peak_force: must be a finite number",
        ),
        # a negative duration was "fitted" (exit 0); a zero peak ran the whole fit, then named a trial value
        (
            lambda: fb.calibrate("seed-experiment", fit=["contact.stiffness"], features={"contact_duration": -6e-4}),
            r"--features contact_duration: must be > 0 s \(got -0.0006\)",
        ),
        (
            lambda: fb.calibrate("seed-experiment", fit=["contact.stiffness"], features={"peak_force": 0.0}),
            r"--features peak_force: must be > 0 N",
        ),
        # --columns without a file to name the columns of: ignored
        (
            lambda: fb.calibrate(
                "seed-experiment", fit=["contact.stiffness"], features={"peak_force": 584.0}, columns={"time": "t"}
            ),
            "--columns: it names the columns of a --data file, and none is given",
        ),  # fmt: skip
        # a role or a feature given twice: the last one won (the velocity column fitted as a force: "success")
        (lambda: parse_columns("time=t,force=F,force=v"), "--columns: the role force is given twice"),
        (lambda: parse_columns("time=t,force=t"), "--columns: the column 't' is given for both time and force"),
        (lambda: parse_features("peak_force=584,peak_force=600"), "--features: peak_force is given twice"),
        # a run that ends inside the first contact: its "peak" was the force at t_end, fitted to 584 N ("success")
        (
            lambda: fb.calibrate(
                "seed-experiment",
                fit=["contact.stiffness"],
                features={"peak_force": 584.0},
                overrides={"solver.t_end": 1e-5},
            ),
            r"solver.t_end: 1e-05 s ends inside the first contact \(from 0 s\), whose end --features peak_force read",
        ),  # fmt: skip
        (
            lambda: fb.calibrate(
                "seed-experiment",
                fit=["contact.stiffness"],
                features={"peak_force": 584.0},
                overrides={"solver.t_end": 1e-5},
                method="fem",
            ),
            r"solver.t_end: 1e-05 s ends inside the first contact",
        ),  # fmt: skip
        # CCM has no contact law: its stiffness and restitution move nothing, and the fit read "success", nfev 1
        (
            lambda: fb.calibrate(
                "seed-experiment",
                fit=["contact.stiffness", "contact.restitution"],
                method="ccm",
                features={"peak_force": 584.0, "contact_duration": 6e-4, "impulse": 0.3},
            ),
            "--fit contact.stiffness, contact.restitution: changes none of the fitted quantities under ccm",
        ),
    ],
)
def test_bad_input_names_the_field(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


def test_missing_column_is_one_line_exit_2(tmp_path):
    data = tmp_path / "m.csv"
    data.write_text("time,force\n0,0\n1e-6,1\n2e-6,2\n")
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "flexbeam.cli",
            "calibrate",
            "seed-experiment",
            "--data",
            str(data),
            "--columns",
            "force=F",
            "--fit",
            "contact.stiffness",
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "--columns force" in r.stderr and "force" in r.stderr


def test_imm_restitution_fits_the_closed_form_of_its_impulse():
    """IMM's impulse at a given pre-impact state is (1 + e) m_eff v, so the restitution that gives a measured impulse
    P is e = (1 + e0) P / P0 - 1 (P0 the case's at e0).  ``calibrate --method imm`` stopped at once before: the first
    record is instantaneous (end = onset = 0), and the window cut to end + 2 x duration set solver.t_end = 0.
    Measured 2.3e-10 from the closed form (scipy's default tolerances, 1e-8 relative); bound 1e-6."""
    e0 = fb.load_case("seed-experiment").contact.restitution
    P0 = fb.simulate(fb.load_case("seed-experiment", {"solver.t_end": 2e-3}), "imm").contacts[0].impulse
    fit = fb.calibrate("seed-experiment", fit=["contact.restitution"], features={"impulse": 0.06}, method="imm")
    assert fit.values[0] == pytest.approx((1.0 + e0) * 0.06 / P0 - 1.0, abs=1e-6)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        # a spreadsheet's UTF-8 byte-order mark: "no time column (columns: \ufefft, F)"
        ("\ufefft,F\n0,0\n1e-6,1\n2e-6,2\n", None),
        # a force column of NaN: "the time column ... must increase strictly" named the wrong column
        ("t,F\n0,nan\n1e-6,nan\n2e-6,nan\n", "fewer than two rows of .* have a finite number in each of 't', 'F'"),
    ],
)
def test_measured_files_read_as_written(tmp_path, text, match):
    data = tmp_path / "m.csv"
    data.write_text(text, encoding="utf-8")
    if match is None:
        m = read_measured(data, {"time": "t", "force": "F"})
        assert m.time.tolist() == [0.0, 1e-6, 2e-6] and m.force.tolist() == [0.0, 1.0, 2.0]
    else:
        with pytest.raises(ParameterError, match=match):
            read_measured(data, {"time": "t", "force": "F"})


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"time": [0.0, 2e-6, 1e-6], "force": [0.0, 1.0, 2.0]}, r"data: the time must increase strictly"),
        ({"time": [0.0, 1e-6, 2e-6], "force": [0.0, np.nan, 2.0]}, r"data: the force holds a value that is no finite"),
        ({"time": [0.0, 1e-6, 2e-6], "force": [0.0, 1.0]}, r"data: the force has 2 values, the time 3"),
        ({"time": [0.0, 1e-6, 2e-6]}, r"data: a measurement needs a force or a velocity history"),
        ({"time": ["a", "b"], "force": [0.0, 1.0]}, r"data: the time must be an array of numbers"),
    ],
)
def test_measurements_built_in_python_are_checked_as_a_files(kwargs, match):
    """A :class:`Measured` passed to ``fb.calibrate`` skipped every check of ``read_measured``: unsorted times were
    fitted, a NaN said "the force column of '' has no positive value", lengths that differ raised a bare IndexError,
    no channel "need at least one array to concatenate" (found by exploratory testing)."""
    from flexbeam.calibrate import Measured

    with pytest.raises(ParameterError, match=match):
        Measured(**{k: np.array(v) if k != "time" or not isinstance(v[0], str) else v for k, v in kwargs.items()})


def test_numpy_numbers_are_features_and_the_budget_is_checked():
    """``features={"peak_force": np.int64(584)}`` was refused ("must be a finite number") where np.float64 passed;
    ``max_nfev=0`` reached scipy's ValueError raw."""
    from flexbeam.calibrate.fitting import _check_budget, _check_measurements

    _check_measurements(None, {"peak_force": np.int64(584), "contact_duration": np.float32(6e-4)}, "ccfm", 0.1)
    for bad in (0, -1, 2.5, True):
        with pytest.raises(ParameterError, match=r"^max_nfev: must be a whole number >= 1"):
            _check_budget(bad)
    with pytest.raises(ParameterError, match=r"^max_nfev"):
        fb.calibrate("seed-experiment", fit=["contact.stiffness"], features={"peak_force": 584.0}, max_nfev=0)
