"""Paper 004: what the batched measurement shares between configurations, and that sharing changes no number.

A scene is keyed by what it reads (the world's entries resolved), and the scenes and runs a worker process computes
come back to the parent's cache, so the later calls of an exploration (the subset search re-measures entries of
earlier configurations) find them whatever the number of workers.
"""

import pytest

from tvtrack.montecarlo import Estimate
from tvtrack.papers.p004_laser_spot_prediction import study
from tvtrack.papers.p004_laser_spot_prediction.register import DEFAULT

SIZE = study.StudySize(
    n_paths=6,
    n_frames=200,
    floor_grid=(3, 5, 10, 30),
    window_grid=(4, 10),
    mlp_hidden_units=8,
    rbf_centres=20,
    train_samples=300,
    n_mc_variance=1000,
    timing_frames=20,
)
CLAIMS = frozenset({"C004-2", "C004-6"})  # the paper's filter only: no network, so the test stays fast


def _values(out):
    """Every number of a claim-values dict (C004-8, a CPU time, is never asked here)."""
    if isinstance(out, dict):
        return {k: _values(v) for k, v in out.items()}
    if isinstance(out, list):
        return [_values(v) for v in out]
    if isinstance(out, Estimate):
        return (out.value, out.ci_low, out.ci_high, out.stderr)
    return out


@pytest.fixture(autouse=True)
def _fresh_cache():
    study.clear_cache()
    yield
    study.clear_cache()


def test_the_band_position_is_no_input_of_a_world_whose_bandwidth_is_set_by_hand():
    """'error in the band' places a calibrated world; at a bandwidth set by hand the scene does not read it (one
    key, one scene), while in a calibrated world it is another scene. The shared scene's values are those of a run
    of its own."""
    by_hand = dict(DEFAULT, bandwidth=8.0)
    moved = dict(by_hand, **{"error in the band": 2.0})
    assert study._scene_key(by_hand, 3, SIZE) == study._scene_key(moved, 3, SIZE)
    assert study._scene_key(DEFAULT, 3, SIZE) != study._scene_key(dict(DEFAULT, **{"error in the band": 2.0}), 3, SIZE)
    assert study._scene_key(by_hand, 3, SIZE) != study._scene_key(by_hand, 4, SIZE)
    a, b = study.measure_batch([by_hand, moved], [3, 3], SIZE, claims=[CLAIMS, CLAIMS])
    assert sum(1 for k in study._CACHE if len(k) == 8) == 1  # one scene for both
    alone = study.measure(moved, 3, SIZE, claims=CLAIMS)
    assert _values(a) == _values(b) == _values({k: alone[k] for k in a})


def test_scenes_from_worker_processes_stay_cached_and_give_the_same_numbers(monkeypatch):
    """Two workers measure two scenes; the parent keeps both scenes and runs, so a later call with a reading
    changed renders nothing (a render would raise here), and every value is that of one process."""
    configs = [dict(DEFAULT, jitter=1.0), dict(DEFAULT, **{"read noise": 16.0})]
    first = study.measure_batch(configs, [5, 5], SIZE, workers=2, claims=[CLAIMS] * 2)
    scenes = [k for k in study._CACHE if len(k) == 8]
    assert len(scenes) == 2 and len(study._CACHE) == 4  # two scenes, two runs of the paper's filter
    readings = [dict(c, reference="true centre") for c in configs]

    def no_render(*args, **kwargs):
        raise AssertionError("a cached scene was rendered again")

    with monkeypatch.context() as m:
        m.setattr(study, "study_run", no_render)
        again = study.measure_batch(readings, [5, 5], SIZE, workers=2, claims=[CLAIMS] * 2)
    study.clear_cache()
    for cfgs, got in ((configs, first), (readings, again)):
        one = study.measure_batch(cfgs, [5, 5], SIZE, workers=1, claims=[CLAIMS] * 2)
        assert _values(got) == _values(one)
        study.clear_cache()
    assert _values(first) != _values(again)  # the reading is read: the truth is another reference


def test_groups_sharing_a_scene_find_it_rendered_once_and_give_the_numbers_of_one_process(monkeypatch, tmp_path):
    """Two scenes, each read at two horizons: four groups (a scene and one run of the methods each) over two
    workers. Each scene is rendered once, before the groups run (two missing: side by side; one shared by two
    groups: in the parent), and every value is that of one process. A horizon with a table row is calibrated
    there (``operating``): its world is another scene, unless the bandwidth is set by hand."""
    log = tmp_path / "renders"
    real = study.study_run

    def counted(*args, **kwargs):  # forked workers inherit it: the file counts their renders too
        with open(log, "a") as f:
            f.write("x")
        return real(*args, **kwargs)

    for configs, renders in (
        ([dict(DEFAULT, jitter=j, horizon=h) for j in (0.0, 1.0) for h in (1, 2)], 2),
        ([dict(DEFAULT, horizon=h) for h in (1, 2)], 1),  # 2 frames: no table row, the default's world
        ([dict(DEFAULT, horizon=h) for h in (1, 10)], 2),  # 10 frames: the world calibrated there, its own scene
        ([dict(DEFAULT, bandwidth=8.0, horizon=h) for h in (1, 10)], 1),  # a bandwidth set by hand: one scene
    ):
        log.write_text("")
        seeds, asked = [5] * len(configs), [CLAIMS] * len(configs)
        with monkeypatch.context() as m:
            m.setattr(study, "study_run", counted)
            got = study.measure_batch(configs, seeds, SIZE, workers=2, claims=asked)
        assert log.read_text() == "x" * renders
        study.clear_cache()
        assert _values(got) == _values(study.measure_batch(configs, seeds, SIZE, workers=1, claims=asked))
        assert _values(got[0]) != _values(got[1])  # the horizon is read
        study.clear_cache()


def test_the_cache_keeps_within_its_byte_budget_and_what_it_drops_is_recomputed_to_the_same_numbers(monkeypatch):
    """The scenes and runs kept between the calls of an exploration stay within the cache's budget (least recently
    used dropped first, never the entry just stored); a configuration measured after its scene was dropped gives the
    numbers of the first measurement, bit for bit."""
    import numpy as np

    from tvtrack.papers.p004_laser_spot_prediction.cache import BoundedCache, nbytes

    small = BoundedCache(max_bytes=3000)
    small["a"], small["b"] = np.zeros(200), np.zeros(150)  # 1600 + 1200 bytes
    assert small["a"].shape == (200,)  # read: "b" is now the least recently used
    small["c"] = np.zeros(100)  # 800 more: over 3000, so "b" goes
    assert set(small) == {"a", "c"} and small.held == 2400
    small["d"] = np.zeros(1000)  # alone over the budget: kept, everything older goes
    assert set(small) == {"d"} and nbytes({"x": [np.zeros(3), (np.zeros(2),)]}) == 40

    first = study.measure_batch([dict(DEFAULT)], [11], size=SIZE, claims=[CLAIMS])
    one_run = study._CACHE.held
    assert one_run > 0
    monkeypatch.setattr(study, "_CACHE", BoundedCache(max_bytes=one_run))  # room for about one scene and run
    other = dict(DEFAULT, jitter=0.5)
    again = study.measure_batch([dict(DEFAULT), other, dict(DEFAULT)], [11, 11, 11], size=SIZE, claims=[CLAIMS] * 3)
    assert study._CACHE.held <= one_run or len(study._CACHE) == 1
    assert _values(again[0]) == _values(first[0]) == _values(again[2])
