"""Tests of paper 003's cost cuts: each faster path gives the same numbers, bit for bit, as the plain one."""

import numpy as np
import pytest

from tvtrack.papers.p003_rotating_marker_tracker.imaging import RotatingMarkerScene


@pytest.mark.parametrize("spot", ["disc", "square"])
def test_spots_rendered_box_by_box_equal_the_whole_crop_render_bit_for_bit(spot):
    rng = np.random.default_rng(4)
    n, size = 200, 26
    scene = RotatingMarkerScene.__new__(RotatingMarkerScene)  # only the spot settings are read
    scene.spot, scene.diameter = spot, 8.0
    crops = rng.normal(size=(n, size, size)).astype(np.float32)
    origin = rng.integers(-50, 50, (n, 2))
    centres = origin + rng.uniform(-12.0, size + 12.0, (n, 2))  # inside, across the edges and outside the crop
    centres[:20] = np.round(centres[:20]) + 0.5 * rng.integers(0, 2, (20, 2))  # on pixel centres and edges
    bright = rng.uniform(0.5, 2.0, n)
    whole = crops + scene._spot(centres, size, origin, bright)
    for threshold in (10**9, 0):  # whole crop, then box by box
        scene.BOX_MIN_PIXELS = {spot: threshold}
        got = crops.copy()
        scene._add_spot(got, centres, origin, bright)
        assert np.array_equal(got, whole), (threshold, np.abs(got - whole).max())
    inside = crops.copy()  # every box inside its crop: the unmasked path
    c_in = origin + rng.uniform(6.0, size - 7.0, (n, 2))
    scene._add_spot(inside, c_in, origin, bright)
    assert np.array_equal(inside, crops + scene._spot(c_in, size, origin, bright))


@pytest.mark.parametrize("spot", ["disc", "square"])
@pytest.mark.parametrize("n", [6, 200])  # whole-crop and box-by-box rendering
def test_spots_of_an_integrated_exposure_rendered_in_one_call_equal_one_call_each(spot, n):
    rng = np.random.default_rng(5)
    size, m = 26, 4
    scene = RotatingMarkerScene.__new__(RotatingMarkerScene)
    scene.spot, scene.diameter = spot, 8.0
    crops = rng.normal(size=(n, size, size)).astype(np.float32)
    origin = rng.integers(-50, 50, (n, 2))
    centres = origin + rng.uniform(-12.0, size + 12.0, (m, n, 2))
    bright = np.stack([np.full(n, 0.25), rng.uniform(0.1, 0.5, n)] * (m // 2))  # marker and decoy interleaved
    one_by_one = crops.copy()
    for j in range(m):
        scene._add_spot(one_by_one, centres[j], origin, bright[j] if j % 2 else 0.25)
    together = crops.copy()
    scene._add_spot(together, centres, origin, bright)
    assert np.array_equal(together, one_by_one)


# --- claims= and the memo of measurement parts: the same numbers as the plain measurement ---------------------------

from tvtrack.papers.p003_rotating_marker_tracker import memo, study  # noqa: E402

TINY = study.Sizes(trials=2, fig1_s=1.5, fig2_s=1.5, transient_s=0.5, horizon_s=0.6)
# The claims= test compares two ways to the same numbers (bit for bit), which does not depend on how long a run is: it
# runs shorter (Fig. 1 0.6 s, Fig. 2 0.5 s, interference 0.3 s), at about 60 % of TINY's time, with every claim's
# parts still measured (as many NaN parts as at TINY, and none more). The memo test below stays at TINY: the batches
# of runs it counts are those of TINY's runs.
SHORT = study.Sizes(trials=2, fig1_s=0.6, fig2_s=0.5, transient_s=0.1, horizon_s=0.3)


def _same(a, b, path=()):
    """Bit-for-bit equality of nested measurement outputs (dicts, lists, arrays, Estimates, numbers)."""
    if isinstance(a, dict):
        assert set(a) == set(b), (path, set(a) ^ set(b))
        for k in a:
            _same(a[k], b[k], path + (k,))
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, path + (i,))
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and np.array_equal(a, b, equal_nan=True), path
    elif hasattr(a, "__dataclass_fields__"):
        _same(vars(a), vars(b), path)
    elif isinstance(a, float) and np.isnan(a):
        assert np.isnan(b), path
    else:
        assert a == b, (path, a, b)


@pytest.mark.parametrize(
    "measure, subsets",
    [
        (study.measure_tracking, [{"C003-1"}, {"C003-3"}, {"C003-4"}, {"C003-9"}, {"C003-2", "C003-4"}]),
        (study.measure_interference, [{"C003-5"}, {"C003-10"}, {"C003-11"}, {"C003-12"}, {"C003-7", "C003-10"}]),
    ],
)
def test_a_measurement_of_some_claims_equals_the_full_one_on_those_claims(measure, subsets):
    config = {"motion_scale": 0.25}
    memo.clear_cache()
    full = measure(config, 3, SHORT)
    for sub in subsets:
        memo.clear_cache()  # computed afresh, not taken from the full run
        part = measure(config, 3, SHORT, claims=frozenset(sub))
        assert {k for k in part if not k.startswith("_")} == sub
        _same({c: part[c] for c in sub}, {c: full[c] for c in sub})
    memo.clear_cache()


@pytest.mark.parametrize(
    "measure, default, changed, reruns",
    [
        # the static baseline's gate changes only the static curves: one batch of runs; since each claim is measured
        # at its configuration projected onto its DEPENDS, the claims that do not read the gate ask their family of
        # curves as a batch of their own, not found under the full run's key: one batch more (a known cost)
        (study.measure_interference, {}, {"static_gate": "2D"}, 2),
        # the Fig. 2 law changes only the Fig. 2 runs; the edge form's normalisation only the two edge-form runs
        (study.measure_tracking, {}, {"fig2_law": "omega 2 Hz"}, 1),
        (study.measure_tracking, {}, {"edge_norm": "slew"}, 2),
    ],
)
def test_reused_parts_give_the_numbers_of_a_fresh_measurement(monkeypatch, measure, default, changed, reruns):
    memo.clear_cache()
    fresh = measure(changed, 5, TINY)
    memo.clear_cache()
    measure(default, 5, TINY)  # the default's parts kept
    calls = []
    monkeypatch.setattr(study, "run_scenario", _counting(study.run_scenario, calls))
    monkeypatch.setattr(study, "run_together", _counting(study.run_together, calls))
    reused = measure(changed, 5, TINY)
    assert len(calls) == reruns
    _same(reused, fresh)
    memo.clear_cache()


def _counting(f, calls):
    """``f`` logging the batches of runs it is asked for (one a call, or a list of prepared batches)."""

    def g(*a, **k):
        calls.extend(a[0] if isinstance(a[0], list) else [1])
        return f(*a, **k)

    return g


@pytest.mark.parametrize("config", [{}, {"exposure": "integrated", "decoy_brightness": "emitted"}])
def test_the_decoy_riding_in_the_rotating_markers_batch_gets_the_runs_it_gets_alone(config):
    sc = study.scenario(config, TINY)
    crit, sirs, d = study.criterion(config, sc), study.SIR_GRID, 2 * sc.diameter
    memo.clear_cache()
    lost, met = study._curve(sc, sirs, 3, 7, crit, (1, 5, ("decoy", d)), True)
    alone_r, met_r = study._curve(sc, sirs, 3, 7, crit, (1, 5), True)
    alone_d, _ = study._curve(study.replace(sc, decoy_offset=d), sirs, 3, 7, crit)
    assert np.array_equal(lost[:2], alone_r) and np.array_equal(met[:2], met_r)
    assert np.array_equal(lost[2], alone_d)
    assert lost[2].any() and not lost[2].all()  # a curve that tells the two apart
    memo.clear_cache()


# --- batches run side by side in one frame loop: each run's numbers as alone -----------------------------------------

from dataclasses import replace  # noqa: E402

from tvtrack.papers.p003_rotating_marker_tracker.lockstep import run_together  # noqa: E402
from tvtrack.papers.p003_rotating_marker_tracker.loops import run_closed_loop, stack_gains  # noqa: E402
from tvtrack.papers.p003_rotating_marker_tracker.scene import (  # noqa: E402
    Scenario,
    prepare_interference,
    prepare_scenario,
)


def _batches(exposure: str) -> list:
    """Batches of every kind the measurements run together: rotating with a decoy block, static (quadrant and
    centroid), another gate, no compensation, per-run gains with full histories, the edge form, another spot, and one
    of other frame times (runs alone)."""
    base = Scenario(duration_s=0.16, n_interferers=5, exposure=exposure)
    sirs, D, g = [0.5, 2.0], base.diameter, lambda s: np.random.default_rng([s, 3])
    quiet = replace(base, n_interferers=0)
    return [
        prepare_interference(
            [g(10) for _ in range(3)],
            3,
            base,
            sirs,
            [{"n_interferers": 1}, {}, {"n_interferers": 0, "decoy_offset": 2 * D}],
        ),
        prepare_interference(
            [g(10) for _ in range(2)], 3, replace(base, rotating=False), sirs, [{"n_interferers": 1}, {}]
        ),
        prepare_interference([g(10)], 3, replace(base, rotating=False, form="centroid"), sirs),
        prepare_interference([g(10)], 3, replace(base, gate_half=6.0), sirs),
        prepare_interference([g(10)], 3, replace(base, kappa=1.0), [1.0, 4.0]),
        prepare_scenario(
            [g(1), g(1)], 6, quiet, n_common=3, gains=stack_gains([replace(quiet, b_xy=b).gains() for b in (5, 20)], 3)
        ),
        prepare_scenario(g(1), 3, replace(quiet, form="edge", spot="square"), keep_full=True),
        prepare_scenario(g(1), 3, replace(quiet, spot="square"), keep_full=False),
        prepare_scenario(g(2), 2, replace(quiet, duration_s=0.1)),
    ]


@pytest.mark.parametrize("exposure", ["instant", "integrated"])
def test_batches_run_side_by_side_give_each_run_its_numbers_alone_bit_for_bit(exposure):
    alone = [run_closed_loop(p.scene, p.tracker, p.rng, **p.loop) for p in _batches(exposure)]
    together = [h for _, _, h in run_together(_batches(exposure))]
    for i, (a, b) in enumerate(zip(alone, together)):
        for f in ("estimate", "gate", "disc", "miss", "inside", "omega"):
            x, y = getattr(a, f), getattr(b, f)
            assert (x is None) == (y is None), (i, f)
            assert x is None or (x.dtype == y.dtype and np.array_equal(x, y)), (i, f)


def test_gate_crops_with_spot_boxes_rendered_ahead_equal_a_plain_render_bit_for_bit():
    """Crops at frames in any order (across the chunks of :meth:`_boxes`), of all trials or a subset, with the decoy lit
    in some trials only, equal the static image plus the marker's and the decoy's spots rendered over the whole crop."""
    sc = Scenario(duration_s=0.4, n_interferers=5, decoy_offset=16.0)
    p = prepare_interference([np.random.default_rng([10, 2]) for _ in range(2)], 3, sc, [0.5, 2.0], [{}, {}])
    scene, m, size = p.scene, RotatingMarkerScene.MARGIN, 26
    scene.decoy_brightness = np.where(np.arange(scene.n) % 3 == 0, 0.0, scene.decoy_brightness)
    scene._lit = np.flatnonzero(scene.decoy_brightness != 0)
    marker, decoys = scene.truth.marker, scene.decoys
    rng = np.random.default_rng(0)
    for k in (150, 3, 70, 63, 64, 199, 0):
        trials = np.arange(scene.n) if k % 2 else np.sort(rng.choice(scene.n, 7, replace=False))
        c = marker[trials, k] + rng.normal(0, 6.0, (trials.size, 2))
        got, origin, _ = scene.gate_crops(k, c, size, None, None if k % 2 else trials)
        for i, t in enumerate(trials):
            ox, oy = origin[i] + m
            want = scene._padded[t, oy : oy + size, ox : ox + size].copy()
            want += scene._spot(marker[t, k][None], size, origin[i][None], 1.0)[0]
            if scene.decoy_brightness[t]:
                want += scene._spot(decoys[t, k][None], size, origin[i][None], scene.decoy_brightness[t : t + 1])[0]
            assert np.array_equal(got[i], want), (k, t)


def test_loss_curves_with_lost_runs_dropped_equal_the_full_runs_bit_for_bit():
    """A loss curve's batch drops its runs once they have lost lock (lockstep ``stop``): the loss indicators and the
    loss criteria met equal those of the full runs (:func:`.scene.interference_runs`, read by :func:`.lock.first_loss`
    and :func:`.lock.loss_criteria` directly), and runs were dropped."""
    from tvtrack.papers.p003_rotating_marker_tracker.curves import curve_part
    from tvtrack.papers.p003_rotating_marker_tracker.lock import LossCriterion, first_loss, loss_criteria
    from tvtrack.papers.p003_rotating_marker_tracker.scene import interference_runs

    sc, crit, sirs, counts = Scenario(duration_s=0.4, n_interferers=5), LossCriterion(12.0, 20), [0.5, 1.0, 3.0], (1, 5)
    key, prepare, finish = curve_part(sc, sirs, 4, 3, crit, counts, True)
    p = prepare()
    ((_, _, h),) = run_together([p])
    lost, met = finish(p, (None, None, h))
    runs = interference_runs(
        [np.random.default_rng([10, 3]) for _ in counts], 4, sc, sirs, blocks=[{"n_interferers": 1}, {}]
    )
    fl = first_loss(runs["miss"], crit, runs["inside"])
    want = loss_criteria(fl, runs["gate"], runs["interferers"], runs["miss"], runs["omega_error"], 20, 4.5, 0.5)
    assert np.array_equal(lost, (fl >= 0).reshape(2, 3, 4)) and np.array_equal(met, want.reshape(2, 3, 4, 3))
    assert np.isnan(h.gate[:, -1]).any() and 0 < lost.sum() < lost.size  # runs were dropped; the curve tells apart


def test_integrated_exposure_crops_with_boxes_rendered_ahead_equal_a_plain_render_bit_for_bit():
    """An integrated exposure's crops (sub-frame boxes rendered ahead, :meth:`_sub_boxes`) equal the static image plus
    the marker's and the decoy's sub-frame spots, interleaved, rendered over the whole crop frame by frame."""
    sc = Scenario(duration_s=0.2, fps=250.0, n_interferers=1, decoy_offset=16.0, exposure="integrated")
    p = prepare_interference([np.random.default_rng([10, 4])], 2, sc, [0.5, 2.0])
    scene, m, size, tr = p.scene, RotatingMarkerScene.MARGIN, 26, p.truth
    steps, dt = scene.exposure_steps, float(tr.t[1] - tr.t[0])
    tau = ((np.arange(steps) + 0.5) / steps - 0.5) * dt
    vel = np.gradient(tr.center, dt, axis=1)
    assert steps > 1
    for k in (40, 2, 17, 16, 49):
        c = tr.marker[:, k] + 2.0
        got, origin, _ = scene.gate_crops(k, c, size, None)
        for t in range(scene.n):
            ox, oy = origin[t] + m
            want = scene._padded[t, oy : oy + size, ox : ox + size].copy()
            a0 = tr.theta[t, k] + scene.decoy_phase[t]
            own = scene.decoys[t, k] - tr.r[t, k] * np.array([np.cos(a0), np.sin(a0)])
            for j in range(steps):
                ang = tr.theta[t, k] + tr.omega[t, k] * tau[j]
                pm = (
                    np.array([tr.xr[t, k], tr.yr[t, k]])
                    + tau[j] * vel[t, k]
                    + tr.r[t, k] * np.array([np.cos(ang), np.sin(ang)])
                )
                a = ang + scene.decoy_phase[t]
                pd = own + tau[j] * vel[t, k] + tr.r[t, k] * np.array([np.cos(a), np.sin(a)])
                want += scene._spot(pm[None], size, origin[t][None], 1.0 / steps)[0]
                want += scene._spot(pd[None], size, origin[t][None], scene.decoy_brightness[t : t + 1] / steps)[0]
            assert np.array_equal(got[t], want), (k, t, np.abs(got[t] - want).max())
