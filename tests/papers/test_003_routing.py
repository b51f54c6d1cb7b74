"""Paper 003: the routing of the two measurements (``measure_tracking``, ``measure_interference``) and their runs.

Each measurement builds its runs as specs (a memo key naming everything a run reads, the generators of its own
stream, the batch, the finish that turns the runs into a claim's parts) and hands each claim the outcome of its own
runs. Here the runs are replaced by recorders: each spec is checked against what the module's text states (the
Fig. 1 batch on stream 1 at every loop bandwidth of the C003-2 mechanism, Fig. 2 on stream 2 with the law of
``fig2_law``, the background sweep on stream 3, the interference curves on the grid of the paper's SIRs, the static
gate of 3D or 2D, the gates of 1.5 D and 5 D, the uncompensated runs at kappa = 1, the decoy 2 D off the object), and
every claim's value is the outcome of the runs it names. No scene is simulated.
"""

from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from tvtrack.montecarlo import ratio_ci
from tvtrack.papers.p003_rotating_marker_tracker import study
from tvtrack.papers.p003_rotating_marker_tracker.curves import SIR_GRID, UNCOMPENSATED_GRID
from tvtrack.papers.p003_rotating_marker_tracker.lock import LossCriterion
from tvtrack.papers.p003_rotating_marker_tracker.loops import stack_gains
from tvtrack.papers.p003_rotating_marker_tracker.memo import scenario_key
from tvtrack.papers.p003_rotating_marker_tracker.register import REGISTER
from tvtrack.papers.p003_rotating_marker_tracker.scene import Scenario

DEFAULT = REGISTER.default()
SIZES = study.Sizes(trials=3, fig1_s=3.0, fig2_s=8.0, transient_s=1.0, horizon_s=2.0)
TRACK = study.measure_tracking.__wrapped__  # beneath the projection onto each claim's DEPENDS
INTERFERE = study.measure_interference.__wrapped__


def draw(rng) -> float:
    return float(rng.random())


def stream(k: int, seed: int) -> float:
    """The first draw of study stream ``k`` of ``seed``: ``default_rng([k, seed])``."""
    return float(np.random.default_rng([k, seed]).random())


def same_gains(a, b):
    for f in ("k_xy", "k_r", "k1", "k2", "k_phi", "k_om"):
        np.testing.assert_array_equal(getattr(a, f), getattr(b, f))


# --- the tracking claims' specs ------------------------------------------------------------------------------------


def test_fig1_runs_every_loop_bandwidth_of_the_mechanism_scaled_by_the_reading_on_stream_1(monkeypatch):
    sc1 = replace(Scenario(), b_xy=5.0)  # a bandwidth reading at half the -3 dB design: every grid point halved
    crit = LossCriterion(7.0, 30, 0.5)
    key, (rngs, runs, sc), kw, finish = study._fig1_spec(sc1, 3, 9, 40, crit)
    assert key == ("fig1", scenario_key(sc1), 3, 9, 40, crit)
    assert len(rngs) == 4 and runs == 12 and sc is sc1
    assert [draw(r) for r in rngs] == [stream(1, 9)] * 4
    same_gains(kw["gains"], stack_gains([replace(sc1, b_xy=b).gains() for b in (1.0, 2.5, 5.0, 10.0)], 3))
    assert kw["n_common"] == 3 and set(kw) == {"gains", "n_common"}
    monkeypatch.setattr(study, "_fig1_outcome", lambda *a: a)
    assert finish("tr", "h") == (sc1, 3, 40, crit, "tr", "h")


def test_fig2_runs_on_stream_2_and_each_quadrant_or_edge_form_on_the_fig1_draws(monkeypatch):
    sc2, crit = replace(Scenario(), omega_mod=0.1), LossCriterion(5.0, 10, 0.5)
    key, (rng, n, sc), kw, finish = study._fig2_spec(sc2, 4, 8, 90)
    assert (key, n, sc, kw) == (("fig2", scenario_key(sc2), 4, 8, 90), 4, sc2, {}) and draw(rng) == stream(2, 8)
    monkeypatch.setattr(study, "_fig2_outcome", lambda *a: a)
    assert finish("tr", "h") == (sc2, 90, "tr", "h")
    edge = replace(Scenario(), form="edge", edge_norm="slew")
    key, (rng, n, sc), kw, finish = study._miss_spec(edge, 4, 8, 30, crit)
    assert (key, n, sc, kw) == (("miss_ms", edge, 4, 8, 30, crit), 4, edge, {"keep_full": False})
    assert draw(rng) == stream(1, 8)
    monkeypatch.setattr(study, "_miss_stats", lambda h, k0, c: (("ms", h, k0, c), "lost"))
    assert finish("tr", "h") == ("ms", "h", 30, crit)
    forms = study._form_runs(replace(Scenario(), spot="disc", b_xy=4.0))
    assert [(s.spot, s.form, s.b_xy) for s in forms] == [
        ("square", "quadrant", 4.0),
        ("square", "edge", 4.0),
        ("disc", "edge", 4.0),
    ]
    assert [s.spot for s in study._form_runs(replace(Scenario(), spot="square"))][:1] == ["disc"]


def test_the_background_sweep_keys_its_batch_and_hands_its_runs_to_the_outcome(monkeypatch):
    sc1, crit = replace(Scenario(), kappa=0.2), LossCriterion(6.0, 20, 0.5)
    key, (rngs, runs, sc), kw, finish = study._background_spec(sc1, 2, 4, 25, crit)
    assert key == ("background", scenario_key(sc1), 2, 4, 25, crit) and runs == 10 and sc is sc1
    assert [draw(r) for r in rngs] == [stream(3, 4)] * 5
    monkeypatch.setattr(study, "_background_outcome", lambda *a: a)
    assert finish("tr", "h") == ("h", 5, 2, 25, crit)


@pytest.fixture
def tracking(monkeypatch):
    """The runs replaced by their outcomes' tags; the parts run together and the C003-9 forms recorded."""
    seen = {"kept": []}
    outcomes = {
        "fig1": {
            "C003-1": "c1",
            "C003-2": "c2",
            "_ripple_trend": "trend",
            "_lock_by_bandwidth": "by bandwidth",
            "quad_ms": {"disc": "quadrant runs"},
            "figure": {"t": "fig1"},
        },
        "fig2": {"C003-3": "c3", "figure": {"t2": "fig2"}},
        "background": ("c4", "case rms"),
    }

    def kept(spec):
        seen["kept"].append(spec[0])
        return outcomes[spec[0][0]]

    monkeypatch.setattr(study, "_kept", kept)
    monkeypatch.setattr(study, "_together", lambda parts: seen.__setitem__("together", [p[0] for p in parts]))
    monkeypatch.setattr(study, "_discriminator_forms", lambda *a: seen.__setitem__("forms", a) or "c9")
    return seen


def test_tracking_hands_each_claim_the_outcome_of_its_own_runs(tracking):
    cfg = {**DEFAULT, "fig2_law": "omega 2 Hz", "loss_radius": "D/2"}
    sizes = replace(SIZES, rotation_hz=6.0)  # the sizes' rotation rate reaches the scenario
    got = TRACK(cfg, 6, sizes)
    sc1 = study.scenario(cfg, sizes, duration_s=3.0)
    assert sc1.rotation_hz == 6.0
    crit = LossCriterion(4.0, 250, 0.5)  # D/2 of the 8 px marker, 0.5 s at 500 Hz
    assert study.criterion(cfg, sc1) == crit
    sc2 = replace(sc1, duration_s=8.0, omega_mod=0.1, omega_mod_hz=2.0, radius_mod=0.15, radius_mod_hz=0.05)
    fig1 = ("fig1", scenario_key(sc1), 3, 6, 500, crit)  # the transient: 1 s at 500 Hz
    fig2 = ("fig2", scenario_key(sc2), 3, 6, 1000)  # a quarter of the 8 s run, longer than the transient
    background = ("background", scenario_key(sc1), 3, 6, 500, crit)
    forms = [("miss_ms", scenario_key(s), 3, 6, 500, crit) for s in study._form_runs(sc1)]
    assert tracking["together"] == [fig1, fig2, background, *forms]
    assert tracking["kept"] == [fig1, fig2, background]
    assert tracking["forms"] == (cfg, sc1, 3, 6, 500, crit, {"disc": "quadrant runs"})
    assert got == {
        "C003-1": "c1",
        "C003-2": "c2",
        "_ripple_trend": "trend",
        "_lock_by_bandwidth": "by bandwidth",
        "C003-3": "c3",
        "C003-4": "c4",
        "C003-9": "c9",
        "_figure": {"t": "fig1", "t2": "fig2", "background_rms": "case rms"},
    }


def test_tracking_runs_only_what_the_claims_asked_read(tracking):
    sizes = replace(SIZES, fig2_s=2.0)  # a quarter of it is shorter than the transient: k2 is the transient
    got = TRACK(DEFAULT, 2, sizes, claims=["C003-3", "C003-11"])
    sc1 = study.scenario(DEFAULT, sizes, duration_s=3.0)
    sc2 = replace(sc1, duration_s=2.0, omega_mod=0.1, omega_mod_hz=0.5, radius_mod=0.15, radius_mod_hz=0.05)
    assert tracking["together"] == tracking["kept"] == [("fig2", scenario_key(sc2), 3, 2, 500)]
    assert got == {"C003-3": "c3", "_figure": {"t2": "fig2"}}
    assert TRACK(DEFAULT, 2, sizes, claims=["C003-4"]) == {"C003-4": "c4", "_figure": {"background_rms": "case rms"}}
    tracking["kept"].clear()
    got = TRACK(DEFAULT, 2, sizes, claims=["C003-9"])  # the quadrant runs of the Fig. 1 batch, then the forms
    assert [k[0] for k in tracking["together"]] == ["fig1", "miss_ms", "miss_ms", "miss_ms"]
    assert [k[0] for k in tracking["kept"]] == ["fig1"]
    assert got == {"C003-9": "c9", "_ripple_trend": "trend", "_lock_by_bandwidth": "by bandwidth"} | {
        "_figure": {"t": "fig1"}
    }
    for alone in ("C003-1", "C003-2"):  # each of the Fig. 1 batch's claims alone runs the batch
        assert TRACK(DEFAULT, 2, sizes, claims=[alone])[alone] == f"c{alone[-1]}"
        assert [k[0] for k in tracking["together"]] == ["fig1"]
    assert TRACK(DEFAULT, 2, sizes, claims=["C003-12"]) == {"_figure": {}}
    tracking["kept"].clear()
    TRACK({k: v for k, v in DEFAULT.items() if k != "fig2_law"} | {"spot": "square"}, 2, sizes, claims=["C003-3"])
    sc1 = study.scenario({**DEFAULT, "spot": "square"}, sizes, duration_s=3.0)
    card = replace(sc1, duration_s=2.0, omega_mod=0.1, omega_mod_hz=0.5, radius_mod=0.15, radius_mod_hz=0.05)
    assert tracking["kept"] == [("fig2", scenario_key(card), 3, 2, 500)]  # Fig. 2's own law where none is named
    tracking["kept"].clear()
    TRACK({**DEFAULT, "fig2_law": "r 0.2 Hz"}, 2, sizes, claims=["C003-3"])
    sc1 = study.scenario(DEFAULT, sizes, duration_s=3.0)
    law = replace(sc1, duration_s=2.0, omega_mod=0.1, omega_mod_hz=0.5, radius_mod=0.25, radius_mod_hz=0.2)
    assert tracking["kept"] == [("fig2", scenario_key(law), 3, 2, 500)]


# --- the interference claims' curves -------------------------------------------------------------------------------


def signature(sc, sirs, counts=None, criteria=False):
    """What a loss curve's runs read of its scenario, as the fakes key them."""
    return (
        sc.rotating,
        sc.gate_half,
        sc.n_interferers,
        sc.kappa,
        sc.decoy_offset,
        sc.form,
        tuple(sirs),
        counts,
        criteria,
    )


@pytest.fixture
def interference(monkeypatch):
    """Each loss curve replaced by its own random indicators (and criteria), keyed by what its runs read."""
    seen = {"curves": {}, "calls": [], "mech": []}
    rng = np.random.default_rng(0)

    def curve(sc, sirs, n, seed, crit, counts=None, criteria=False):
        key = signature(sc, sirs, counts, criteria)
        seen["calls"].append((key, n, seed, crit))
        shape = (len(sirs), n) if counts is None else (len(counts), len(sirs), n)
        if key not in seen["curves"]:
            seen["curves"][key] = (rng.random(shape) < 0.5, rng.random(shape + (3,)) < 0.5 if criteria else None)
        return seen["curves"][key]

    def extend(curves, sirs, more, max_points, trigger):
        seen["extend"] = (dict(curves), sirs, max_points, trigger)
        seen["more"] = more([k for k in curves if k != ("rotating", 5)], 9.0)
        return np.array([0.25, *SIR_GRID]), {k: ("extended", k) for k in curves}

    monkeypatch.setattr(study, "_curve", curve)
    monkeypatch.setattr(study, "_together", lambda parts: seen.__setitem__("together", list(parts)))
    monkeypatch.setattr(study, "curve_part", lambda *a: ("part",) + a)
    monkeypatch.setattr(study, "memo", lambda key, compute: seen.__setitem__("memo", key) or compute())
    monkeypatch.setattr(study, "_bandwidth_ratio", lambda *a: seen.__setitem__("bandwidth", a) or "bandwidth ratio")
    monkeypatch.setattr(study, "extend_grid", extend)
    monkeypatch.setattr(study, "interference_claims", lambda *a: seen.__setitem__("claims", a) or {"C003-5": "v"})
    monkeypatch.setattr(
        study, "loss_mechanisms", lambda lost, met: seen["mech"].append((lost, met)) or len(seen["mech"]) - 1
    )
    monkeypatch.setattr(study, "threshold", lambda lost, sirs: ("threshold", lost, len(sirs)))
    monkeypatch.setattr(study, "threshold_bound", lambda lost, sirs: ("bound", lost, len(sirs)))
    return seen


def test_interference_runs_each_curve_on_its_scenario_criterion_and_grid(interference):
    cfg = {**DEFAULT, "static_gate": "2D", "static_form": "centroid"}
    got = INTERFERE(cfg, 4, SIZES)
    base = study.interference_scenario(cfg, SIZES)
    crit, sirs, usirs = study.criterion(cfg, base), tuple(SIR_GRID), tuple(UNCOMPENSATED_GRID)
    st = replace(base, rotating=False, gate_half=8.0, form="centroid")  # the 2D gate: half of it is D
    gates = {1.5: replace(base, n_interferers=5, gate_half=6.0), 5.0: replace(base, n_interferers=5, gate_half=20.0)}
    unc = replace(base, n_interferers=5, kappa=1.0)
    decoy = replace(base, decoy_offset=16.0)
    crits = {"st": LossCriterion(8.0, 250, 0.5), 1.5: LossCriterion(6.0, 250, 0.5), 5.0: LossCriterion(20.0, 250, 0.5)}
    fam = (1, 5, ("decoy", 16.0))
    calls = [(signature(base, sirs, fam, True), crit), (signature(st, sirs, (1, 5), True), crits["st"])]
    calls += [(signature(g, sirs), crits[f]) for f, g in gates.items()] + [(signature(unc, usirs), crit)]
    calls += [(signature(base, [9.0], (1, 5)), crit), (signature(st, [9.0], (1, 5)), crits["st"])]
    calls += [(signature(decoy, [9.0]), crit)]
    assert [(k, c) for k, _, _, c in interference["calls"]] == calls
    assert {(n, seed) for _, n, seed, _ in interference["calls"]} == {(3, 4)}
    parts = [("part", base, sirs, 3, 4, crit, fam, True), ("part", st, sirs, 3, 4, crits["st"], (1, 5), True)]
    parts += [("part", g, sirs, 3, 4, crits[f]) for f, g in gates.items()] + [("part", unc, usirs, 3, 4, crit)]
    together = interference["together"]
    assert [tuple(tuple(x) if isinstance(x, np.ndarray) else x for x in p) for p in together[:-1]] == parts
    bw_key = ("bandwidth", scenario_key(base), 3, 4, 500)
    assert together[-1][0] == bw_key and interference["memo"] == bw_key
    assert interference["bandwidth"] == (base, 3, 4, 500) and interference["claims"][0] == cfg
    assert got["_bandwidth_ratio"] == "bandwidth ratio" and got["C003-5"] == "v"
    _curves_are_handed_on(interference, got, base, st, gates, unc)


def _curves_are_handed_on(seen, got, base, st, gates, unc):
    c = seen["curves"]
    lost_r, met_r = c[signature(base, SIR_GRID, (1, 5, ("decoy", 16.0)), True)]
    lost_s, met_s = c[signature(st, SIR_GRID, (1, 5), True)]
    want = {("rotating", 1): lost_r[0], ("rotating", 5): lost_r[1], ("static", 1): lost_s[0], ("static", 5): lost_s[1]}
    want |= {("gate", f): c[signature(g, SIR_GRID)][0] for f, g in gates.items()}
    want |= {"decoy": lost_r[2], "uncompensated": c[signature(unc, UNCOMPENSATED_GRID)][0]}
    cfg, base_, curves, capt, xc, xsirs, bw, asked = seen["claims"]
    assert base_ == base and bw == "bandwidth ratio" and asked == set(study.I_CLAIMS)
    assert set(curves) == set(want)
    for k, v in want.items():
        np.testing.assert_array_equal(curves[k], v)
    np.testing.assert_array_equal(capt, met_r[1, :, :, 0])  # captures: five interferers, the first criterion
    pairs = [("rotating", 1), ("rotating", 5), ("static", 1), ("static", 5), "decoy"]
    ext, sirs, max_points, trigger = seen["extend"]
    assert list(ext) == pairs and all(np.array_equal(ext[k], want[k]) for k in pairs)
    assert list(sirs) == list(SIR_GRID) and max_points == 1 and trigger == pairs[:2]
    more = seen["more"]  # one more SIR: each family asked from its own curve at that SIR, the decoy alone
    r9, s9 = c[signature(base, [9.0], (1, 5))][0], c[signature(st, [9.0], (1, 5))][0]
    dec = c[signature(replace(base, decoy_offset=16.0), [9.0])][0]
    assert set(more) == set(pairs)
    for k, v in {("rotating", 1): r9[0, 0], ("rotating", 5): r9[1, 0], ("static", 1): s9[0, 0]}.items():
        np.testing.assert_array_equal(more[k], v)
    np.testing.assert_array_equal(more[("static", 5)], s9[1, 0])
    np.testing.assert_array_equal(more["decoy"], dec[0])
    assert xc == {k: ("extended", k) for k in pairs} and list(xsirs) == [0.25, *SIR_GRID]
    keys = [("rotating", 1), ("rotating", 5), ("static", 1), ("static", 5)]
    assert got["_mechanisms"] == {f"{m} {k}": i for i, (m, k) in enumerate(keys)}
    for (lost, met), key, m in zip(seen["mech"], keys, (met_r[0], met_r[1], met_s[0], met_s[1])):
        np.testing.assert_array_equal(lost, want[key])  # each curve with its own loss criteria
        np.testing.assert_array_equal(met, m)
    assert got["_map"] == {f"{m} {k}": ("threshold", ("extended", (m, k)), 9) for m, k in keys}
    assert got["_map_bound"] == {f"{m} {k}": ("bound", ("extended", (m, k)), 9) for m, k in keys}
    assert got["_grid"] == [0.25, *SIR_GRID] and all(type(x) is float for x in got["_grid"])
    names = {"rotating/1", "rotating/5", "static/1", "static/5", "gate/1.5", "gate/5.0", "decoy", "uncompensated"}
    assert set(got["_curves"]) == names and got["_curves"]["gate/1.5"] is want["gate", 1.5]


def test_interference_runs_only_the_curves_the_claims_asked_read(interference):
    base = study.interference_scenario(DEFAULT, SIZES)
    crit, sirs = study.criterion(DEFAULT, base), tuple(SIR_GRID)
    got = INTERFERE(DEFAULT, 1, SIZES, claims=["C003-10"])  # the gates and the uncompensated runs
    gates = [replace(base, n_interferers=5, gate_half=h) for h in (6.0, 20.0)]
    unc = replace(base, n_interferers=5, kappa=1.0)
    calls = [signature(base, sirs, (1, 5), True)] + [signature(g, sirs) for g in gates]
    calls += [signature(unc, UNCOMPENSATED_GRID), signature(base, [9.0], (1, 5))]
    assert [k for k, _, _, _ in interference["calls"]] == calls
    parts = [("part", base, sirs, 3, 1, crit, (1, 5), True)] + [("part", g, sirs, 3, 1, crit) for g in gates]
    parts[1:] = [p[:5] + (study.criterion(DEFAULT, g),) for p, g in zip(parts[1:], gates)]
    parts += [("part", unc, tuple(UNCOMPENSATED_GRID), 3, 1, crit)]
    together = [tuple(tuple(x) if isinstance(x, np.ndarray) else x for x in p) for p in interference["together"]]
    assert together == parts  # neither the static marker's curves nor the bandwidth runs
    assert interference["claims"][-1] == {"C003-10"} and interference["claims"][-2] is None  # no bandwidth ratio
    assert "memo" not in interference and "_bandwidth_ratio" not in got and "_map" not in got
    assert list(got["_mechanisms"]) == ["rotating 1", "rotating 5"]
    assert set(got["_curves"]) == {"rotating/1", "rotating/5", "gate/1.5", "gate/5.0", "uncompensated"}
    interference["calls"].clear()
    unnamed = {k: v for k, v in DEFAULT.items() if k not in ("static_gate", "static_form")}
    got = INTERFERE(unnamed, 1, SIZES, claims=["C003-12", "C003-1"])  # the static marker and the decoy
    st = replace(base, rotating=False, gate_half=12.0, form="quadrant")  # the 3D gate, the quadrant form: unnamed
    calls = [signature(base, sirs, (1, 5, ("decoy", 16.0)), True), signature(st, sirs, (1, 5), True)]
    calls += [signature(base, [9.0], (1, 5)), signature(st, [9.0], (1, 5))]
    calls += [signature(replace(base, decoy_offset=16.0), [9.0])]
    assert [k for k, _, _, _ in interference["calls"]] == calls
    assert [c for _, _, _, c in interference["calls"]][1] == LossCriterion(12.0, 250, 0.5)  # 1.5 D
    assert set(got["_map"]) == {"rotating 1", "rotating 5", "static 1", "static 5"}
    assert [p[1] for p in interference["together"]] == [base, st]  # no gate, uncompensated or bandwidth runs
    assert interference["claims"][-1] == {"C003-12"}
    interference["calls"].clear()
    INTERFERE(DEFAULT, 1, SIZES, claims=["C003-11"])
    assert interference["memo"] == ("bandwidth", scenario_key(base), 3, 1, 500)
    assert [signature(g, sirs) for g in gates] == [k for k, _, _, _ in interference["calls"]][1:3]


def test_the_bandwidth_pair_runs_on_the_fig1_draws_at_5_and_20_hz(monkeypatch):
    base = replace(Scenario(), b_xy=7.0)
    rngs, runs, sc = study._bandwidth_runs(base, 3, 12)
    assert [draw(r) for r in rngs] == [stream(1, 12)] * 2 and runs == 6 and sc is base
    kw = study._bandwidth_kw(base, 3)
    assert kw["n_common"] == 3 and set(kw) == {"n_common", "gains"}
    same_gains(kw["gains"], stack_gains([replace(base, b_xy=5.0).gains(), replace(base, b_xy=20.0).gains()], 3))
    key, prepare, finish = study._bandwidth_part(base, 3, 12, 40)
    assert key == ("bandwidth", scenario_key(base), 3, 12, 40)
    seen = {}
    monkeypatch.setattr(study, "prepare_scenario", lambda *a, **k: seen.setdefault("prepare", (a, k)) and "batch")
    assert prepare() == "batch"
    (r, n, s), k = seen["prepare"]
    assert [draw(x) for x in r] == [stream(1, 12)] * 2 and (n, s) == (6, base) and k["keep_full"] is False
    assert k["n_common"] == 3
    same_gains(k["gains"], kw["gains"])
    miss = np.vstack([np.full((3, 50), 2.0), np.full((3, 50), 3.0)])
    miss[1, 45:] = 9.0  # after k0 = 40: read
    miss[4, :40] = 99.0  # before k0: not read
    got = finish(None, (None, None, SimpleNamespace(miss=miss)))
    ms = np.mean(miss[:, 40:] ** 2, axis=1).reshape(2, 3)
    want = ratio_ci(ms[1], ms[0])  # 20 Hz over 5 Hz
    assert (got.value, got.ci_low, got.ci_high) == (want.value, want.ci_low, want.ci_high)
    assert got.value == pytest.approx(9.0 / ((4.0 + (4.0 + 81.0) / 2 + 4.0) / 3), rel=1e-12)
