"""Notebook 004: C004-6's scored frames, the register in plain words and honest kinds."""

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction import predictors as pr
from tvtrack.papers.p004_laser_spot_prediction import side_studies as side
from tvtrack.papers.p004_laser_spot_prediction import study
from tvtrack.papers.p004_laser_spot_prediction.prediction_study import PAPER
from tvtrack.papers.p004_laser_spot_prediction.register import DEFAULT, DEPENDS, PINNED, build
from tvtrack.papers.p004_laser_spot_prediction.sizes import screen_size

from . import test_004_study as _study
from tvtrack.papers.p004_laser_spot_prediction import world

SIZE, run = _study.SIZE, _study.run  # the study tests' reduced size and their default run (fixture)


def _late_ratio(fc_a, fc_b, ref, first: int) -> float:
    """sqrt(mean over paths of the MSE of a / that of b), one-step errors e[n] = f[n-1] - ref[n], n >= first."""
    ea = fc_a[0, ..., first - 1 : -1] - ref[0, ..., first:]
    eb = fc_b[0, ..., first - 1 : -1] - ref[0, ..., first:]
    return float(np.sqrt(np.mean(np.mean(ea**2, axis=(-2, -1))) / np.mean(np.mean(eb**2, axis=(-2, -1)))))


def test_c004_6_scores_the_second_half_of_the_frames(run):
    """C004-6 is the RMS over frames T/2..T-1 (frames 500-1000 of 1000, as set here) without the floor over with
    the cross-validated floor, against the measured centre; recomputed here from the forecasts. The ratio over all
    scored frames differs, so a run scoring the wrong frames fails."""
    T = run.truth.shape[-1]
    nofloor = pr.growing_memory_forecast(run.z, 1, 2, None)
    want = _late_ratio(nofloor, run.forecasts[PAPER], run.z_meas, T // 2)
    got = study.claim_values(run, 7)["C004-6"]
    assert got.value == pytest.approx(want, rel=1e-12)
    wrong = _late_ratio(nofloor, run.forecasts[PAPER], run.z_meas, SIZE.eval_start)
    assert wrong != pytest.approx(want, rel=1e-3)  # the frames matter: the pin can see a wrong start
    truth = study.claim_values(study.replace(run, config=dict(DEFAULT, reference="true centre")), 7)["C004-6"]
    assert truth.value == pytest.approx(_late_ratio(nofloor, run.forecasts[PAPER], run.truth, T // 2), rel=1e-12)


def test_every_entry_and_value_in_plain_words():
    reg = build()
    for e in reg:
        assert e.title and e.title != e.name or " " in e.name
        for v in e.values:
            assert v in e.phrases and len(e.phrases[v]) > 5, (e.name, v)
    assert "calibrated" in reg["bandwidth"].phrase(reg["bandwidth"].default)


def test_kinds_say_reading_or_world_honestly():
    """Lost frames are a world beyond the paper (its recursion never meets one), so the pinned C004-4 condition is
    all world and its flip reads 'does not extend to lost frames'; the horizon and the frame rate are readings of
    the paper's text (unstated horizon, '25 frames/s' against 'every 5 ms'); the noise law is a world."""
    reg = build()
    assert reg["lost frames"].side == reg["frame loss"].side == "world"
    assert all(reg[name].side == "world" for name in PINNED[0])
    assert all(reg[name].values.count(v) == 1 for cond in PINNED for name, v in cond.items())  # register values
    assert reg["horizon"].side == reg["frame rate"].side == "reading"
    assert reg["C004-5 noise"].side == "world"
    assert set(DEPENDS["C004-5"]) == {"C004-5 noise"}


def test_spline_readings_are_tuned_on_the_extended_window_grid():
    """With a window grid of 4 alone every fold picks the grid's top, so the tuning tries 45, 70, 100 (as for the
    interpolating spline and the regressions): in a slow, noisy world the least-squares cubic picks a longer window, and each
    path's forecast is the one of its chosen window. The variant floor is tuned over the floors likewise."""
    size = study.replace(SIZE, window_grid=(4,))
    cfg = dict(DEFAULT, bandwidth=1.0, **{"read noise": 64.0})  # slow, noisy: long windows
    # every method but the networks, which nothing here reads: each part's numbers are those of a full run
    r = study._methods(study.study_run(cfg, 7, size), cfg, 7, study.ALL_PARTS - {"learned"})
    for name, make in (
        (study.LSQ_CUBIC, lambda L: pr.sliding_regression_forecast(r.z, L, 3, 1)),
        (study.NATURAL_SPLINE, lambda L: pr.natural_spline_forecast(r.z, L, 1)),
    ):
        chosen = np.asarray(r.comparison.chosen[name])
        assert set(chosen) <= {4, 45, 70, 100}
        for p, L in enumerate(chosen):
            np.testing.assert_allclose(r.forecasts[name][:, p], make(int(L))[:, p], equal_nan=True)
    assert np.max(r.comparison.chosen[study.LSQ_CUBIC]) >= 45
    variant = np.asarray(r.comparison.chosen["growing memory, g1 floor (variant)"])
    assert set(variant) <= set(size.floor_grid) | {200, 350}
    assert side.grid_edge_report(r)[study.LSQ_CUBIC] >= 0.0


def test_model_order_result_states_its_numbers(run):
    """Beside C004-3: the best first-order and best second-order predictors with their RMS, the MSE ratio
    (recomputed from the forecasts) and the acceleration's correlation time in frames and ms (40 ms a frame)."""
    from tvtrack.papers.p004_laser_spot_prediction import findings as fd
    from tvtrack.papers.p004_laser_spot_prediction.prediction_study import per_trial_path_mse

    s = side.model_order_summary(run)
    mse = {n: per_trial_path_mse(run.forecasts[n], run.z_meas, 1, SIZE.eval_start)[0] for n in run.forecasts}
    order1 = ("finite differences, 2 points", "linear regression deg 1")
    b1 = min(order1, key=lambda n: mse[n].mean())
    assert s["best_order1"] == b1
    assert s["ratio_2_over_1"].value == pytest.approx(mse[s["best_order2"]].mean() / mse[b1].mean(), rel=1e-12)
    assert s["frame_ms"] == pytest.approx(40.0)
    text = fd.model_order_sentence(s)
    tau = s["singer_tau_frames"]
    assert f"RMS {np.sqrt(mse[b1].mean()):.3f} px" in text
    assert f"({np.min(tau) * 40:.2g}..{np.max(tau) * 40:.2g} ms)" in text


def test_flips_markdown_is_short_and_plain():
    """One line per claim part with its flips in plain words (each marked reading or world), at most max_flips
    named and the rest counted, the share in the core's three numbers, and the entries its value moves with by title;
    no run table."""
    from tvtrack.papers.p004_laser_spot_prediction import findings as fd

    flips = [
        {"verdict": "reproduced", "text": f"condition {k}", "side": "reading" if k % 2 else "world"} for k in range(9)
    ]
    part = {
        "verdict": "not reproduced",
        "label": "depends",
        "share": {
            "agree": 20,
            "flip": 10,
            "undecided": 8,
            "design": 38,
            "decided": 30,
            "ci_low": 0.36,
            "ci_high": 0.69,
        },
        "flips": flips,
        "runs_to_decide": None,
        "sensitivity": [{"title": "prediction horizon", "score": 0.6}, {"title": "spline", "score": 0.05}],
    }

    class Ex:
        def record(self, cid, rule):
            return {"parts": {"a": part, "b": dict(part, flips=[], label="robust")}}

    text = fd.flips_markdown(Ex(), {"C004-3": None}, max_flips=3)
    lines = text.splitlines()
    assert len(lines) == 2 and lines[0].startswith("- **C004-3 (a)**: not reproduced, depends")
    assert "reproduced when condition 0 (world); reproduced when condition 1 (reading)" in lines[0]
    assert "condition 3" not in lines[0] and "; 6 more" in lines[0]
    # the share over every explored configuration, as the core says it; never agree of the decided ones only
    assert "20 agree, 10 flip and 8 stay undecided of 38 explored configurations" in lines[0]
    assert (
        "20 of 30" not in lines[0] and "(share of the 38 explored configurations agreeing 0.36-0.69, 95 %)" in lines[0]
    )
    assert "moves most with: prediction horizon." in lines[0]
    assert "flips" not in lines[1] and "spline" not in lines[1]


def test_screen_is_the_same_study_on_less_data():
    """The joint design's screen keeps the paths, folds and grids of the floor and windows (the verdicts read the
    same comparisons) and halves the frames, quarters the training pairs and the variance check, and keeps the
    lag grid's two ends; never below the smallest run the parameters allow, and no screen below 400 frames."""
    full = study.StudySize()
    s = screen_size(full)
    assert (s.n_paths, s.n_folds, s.floor_grid, s.window_grid) == (
        full.n_paths,
        full.n_folds,
        full.floor_grid,
        full.window_grid,
    )
    assert (s.n_frames, s.train_samples, s.n_mc_variance, s.lag_grid) == (500, 1000, 5000, (1, 16))
    assert screen_size(SIZE) == SIZE  # 200 frames: nothing to halve, so no screen
    mid = screen_size(study.replace(SIZE, n_frames=400))
    assert mid.n_frames == 200 and mid.train_samples == 300 and mid.lag_tuning_samples <= mid.train_samples


def test_variant_floor_forecast():
    """The variant floor at N_f >= T never binds (g_N1 >= g_T1 for N <= T): the growing memory without a floor.
    At N_f = 10 its position gain never falls below g_{10,1} while the paper's frozen floor differs."""
    from tvtrack.filters.polynomial import growing_memory_gains, predict_ahead

    rng = np.random.default_rng(3)
    z = (
        20
        + np.cumsum(np.cumsum(0.05 * rng.standard_normal((2, 150)), axis=-1), axis=-1)
        + 0.2 * rng.standard_normal((2, 150))
    )
    np.testing.assert_allclose(
        pr.g1_floor_forecast(z, 150, 2), pr.growing_memory_forecast(z, 2, 2, None), rtol=1e-9, equal_nan=True
    )
    g = pr.g1_floor_gains(2, 150, growing_memory_gains(2, 10)[-1, 0])
    assert np.nanmin(g[:, 0]) == pytest.approx(growing_memory_gains(2, 10)[-1, 0])
    states = pr.g1_floor_filter(z, growing_memory_gains(2, 10)[-1, 0])
    np.testing.assert_allclose(pr.g1_floor_forecast(z, 10, 3), predict_ahead(states, 3), rtol=1e-12, equal_nan=True)
    assert not np.allclose(pr.g1_floor_forecast(z, 10)[:, 20:], pr.growing_memory_forecast(z, 1, 2, 10)[:, 20:])


def test_c004_4_lost_frame_flip_reads_limited_not_depends():
    """The pinned lost-frame condition that breaks the recursion is a world beyond the paper: the core labels the
    part `limited` and names the flip as a world, in plain words ("frames lost ...; lost frames skipped ...")."""
    from tvtrack.labels import label_parts
    from tvtrack.montecarlo import Estimate
    from tvtrack.papers.p004_laser_spot_prediction.claims import RULES

    reg = build()
    rule = RULES["C004-4"]
    exact = lambda v: Estimate.exact(v)  # noqa: E731  (a deterministic computation)
    reps = [{"seed": s, "measured": exact(1e-13)} for s in range(3)]
    conds = [{"changed": dict(PINNED[0]), "kind": "pinned", "measured": exact(1.3)}]
    conds += [{"changed": {"frame loss": 0.01}, "kind": "single", "measured": exact(1e-13)}]
    conds += [{"changed": {"lost frames": "skipped (coast)"}, "kind": "single", "measured": exact(1e-13)}]
    rec = label_parts(rule, exact(1e-13), reps, conds, [reg[k] for k in DEPENDS["C004-4"]], deterministic=True)
    assert rec["label"] == "limited"
    (flip,) = rec["parts"]["claim"]["flips"]
    assert flip["side"] == "world" and "frames lost" in flip["text"] and "coasts" in flip["text"]


def test_paths_are_drawn_again_until_the_spot_stays_on_the_sensor():
    """At amplitude 2 (6-16 px RMS) some sets of 15 x 1000 frames reach the sensor's edge, which the generator
    refuses (a joint configuration crashed the exploration): the set is drawn again from a child of the run's
    stream. A set that stays on the sensor is the first draw, unchanged."""
    size = study.StudySize()
    scene = study.scene_config(dict(DEFAULT, amplitude=2.0, bandwidth=3.0), size)  # the factor of these draws
    first = lambda seed: int(study.run_streams(seed)[0].generate_state(1)[0])  # noqa: E731
    with pytest.raises(ValueError, match="leave the sensor"):
        world.exposed_traces(scene, first(1), "instant")
    tr, draws = study.traces_on_sensor(scene, study.run_streams(1)[0], "instant")
    assert draws == 2 and tr.centres_px.min() >= -0.5 and tr.centres_px.max() <= 127.5
    same, one = study.traces_on_sensor(scene, study.run_streams(0)[0], "instant")
    assert one == 1
    np.testing.assert_array_equal(same.centres_px, world.exposed_traces(scene, first(0), "instant").centres_px)
