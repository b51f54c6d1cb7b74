"""Every paper's register entries, checked against what they say and what reads them.

1. **Kinds said in words.** An entry's ``why`` says which of the three kinds it is, in words a reader finds, and
   says no other: the keyword rule is that the text contains a phrase of its own side and none of another's
   (case-insensitive):

   - a *reading* of the paper's text (kinds ``reading``, ``statistic``, ``comparator``): "a reading of",
     "readings of", "ambiguous", "the paper says";
   - an *unreported setting* of the paper's own experiment: "unreported setting", "the paper's own experiment",
     "never printed";
   - a *world* beyond the paper (``regime``, ``model``, ``operating point``, ``scale``): "beyond the paper".

   So an entry whose text calls it a reading, or quotes what "the paper says" as the ambiguity, while its kind is
   a world fails, and so does a world or setting that calls itself a reading. The phrases are few and plain on
   purpose: each ``why`` justifies its kind with the paper's line in one of them.
2. **Declared entries.** Each claim of every paper is measured alone, at the default, on small sizes, under
   :func:`tvtrack.explore.check_declared`: a measurement that uses a register entry its claim's ``DEPENDS``
   does not declare fails, naming the claim and the entry.

Every paper package the contract finds (:func:`tvtrack.contract.paper_packages`) must have its measurements in
:data:`MEASUREMENTS` (a new paper adds its own there).
"""

from __future__ import annotations

import functools
import importlib
import re

import pytest

from tvtrack import contract
from tvtrack.explore import check_declared

PACKAGES = contract.paper_packages()

#: The phrases that say an entry's side (see the module docstring).
SIDE_PHRASES = {
    "reading": ("a reading of", "readings of", "ambiguous", "the paper says"),
    "setting": ("unreported setting", "the paper's own experiment", "never printed"),
    "world": ("beyond the paper",),
}


def sides_said(why: str) -> set[str]:
    """The sides whose phrases ``why`` contains."""
    text = " ".join(why.lower().split())
    return {side for side, phrases in SIDE_PHRASES.items() if any(p in text for p in phrases)}


def test_the_keyword_rule_tells_the_three_sides_apart():
    assert sides_said("A reading of l. 185's 'mean rotation frequency'") == {"reading"}
    assert sides_said("the paper's own experiment had a rate law it never printed") == {"setting"}
    assert sides_said("a world beyond the paper: Poisson counts") == {"world"}
    assert sides_said("the paper says 1-2 px; a world beyond the paper") == {"reading", "world"}
    assert sides_said("not stated") == set()


def _entries():
    for name in PACKAGES:
        package = importlib.import_module(f"tvtrack.papers.{name}")
        for entry in package.REGISTER:
            yield pytest.param(entry, id=f"{name[:4]}:{entry.name}")


@pytest.mark.parametrize("entry", list(_entries()))
def test_every_entry_says_its_own_kind_and_no_other(entry):
    said = sides_said(entry.why)
    assert said == {entry.side}, (
        f"{entry.name!r} is a {entry.kind} (side {entry.side!r}) but its why says {sorted(said) or 'no side'}: "
        f"{entry.why!r}"
    )


# ----------------------------------------------------------------------------------- declared entries


def _p000():
    from tvtrack.papers.p000_dissector_ekf import study
    from tvtrack.papers.p000_dissector_ekf.register import DEPENDS, REGISTER
    from tvtrack.register import Register

    sizes = study.Sizes(
        n_trials=8,
        duration_T=6.0,
        window_T=2.0,
        substeps=2,
        psi_grid=(5.0, 50.0),
        contrast_grid=(0.0, 0.5, 0.9),
        dt_points=((20.0, 0.5),),
        dt_factor=2,
        dt_trials=8,
        dt_duration_T=4.0,
        grid_trials=4,
        grid_points=41,
    )
    cost = Register([REGISTER[k] for k in DEPENDS["C000-4"]])
    # study.measure projects each claim's configuration onto its DEPENDS itself (every other entry reset to the
    # register's default), so the guard watches the claim's own function beneath it, as measure calls it, at the
    # configuration the projection gives for the declared entries. Let through, each for the reason given:
    single = {"C000-1": study._c1, "C000-2": study._c2, "C000-3": study._c3, "C000-6": study._c6}
    single |= {"C000-8": study._c8, "C000-9": study._c9}

    def beneath(config, seed, sizes, claims):
        out = {}
        for cid in claims:
            if cid in ("C000-5", "C000-7"):  # one computation, as measure makes it
                c5, c7 = study._c5_c7(config, seed, sizes)
                out[cid] = c5 if cid == "C000-5" else c7
            else:
                out[cid] = single[cid](config, seed, sizes)
        return out

    unused = {cid: set() for cid in DEPENDS}
    # C000-7 is computed with C000-5: C000-5's two readings shape C000-5's parts, never C000-7's trend or gap
    unused["C000-7"] |= {"C000-5 comparison", "substantially determines"}
    # C000-6 and C000-8 are measured at the paper's stated sigma_1 = 0.1 T ("typical normalised message parameters",
    # Results) on purpose, to spare their costliest runs (C000-6's grid-filter and PCRLB references at P = 0.9, C000-8's
    # two-rate simulation, where at 0.2 T variant 1's lock losses leave the 3 % check undecidable: docs/validity/000.md);
    # tests/papers/test_000_study.py pins that both read it at its default
    unused["C000-6"] |= {"sigma_1"}
    unused["C000-8"] |= {"sigma_1"}
    depends = {cid: [*names, *sorted(unused[cid] - set(names))] for cid, names in DEPENDS.items()}
    return [
        (functools.partial(beneath, sizes=sizes), REGISTER, depends, list(study.MEASURED_CLAIMS)),
        (functools.partial(study.measure_cost, n_trials=4, n_steps=20), cost, depends, ["C000-4"]),
    ]


def _p001():
    from tvtrack.papers.p001_maneuver_occlusion_kf import curves, spherical, study
    from tvtrack.papers.p001_maneuver_occlusion_kf.register import DEPENDS, GROUPS, build_register

    reg = build_register()
    sizes = dict(
        n_trials=20,
        n_fa_runs=300,
        fa_duration_s=12.0,
        roc_delay_s=0.5,
        step_dv=1.0,
        sigma_eps=1.0,
        n_tradeoff_trials=6,
        n_train=2,
        train_seed=5,
        kb3_grid=[20, 50, 100, 200],
        loss_grid_s=[6.0, 8.0, 12.0],
        n_fig4_trials=20,
        defaults=reg.default(),
        grids=dict(
            fixed2=(2, 10), fixed3=(3, 20), imm_q_ca=(1e-3,), imm_p_stay=(0.99,), vdf_q_ca=(1e-5,), vdf_windows=(5,)
        ),
        prediction_rms=1.0,
    )
    # the detection and curve claims are projected onto their DEPENDS (tvtrack.projection.as_declared), so the guard
    # watches the measurements beneath the decorator (the other two take the configuration as it comes)
    fns = {
        "detection": study.measure_detection.__wrapped__,
        "tradeoff": study.measure_tradeoff,
        "curves": curves.measure_curves.__wrapped__,
        "spherical": spherical.measure_spherical,
    }
    # every claim builds the scenario, and the detection claims the no-manoeuvre runs; the guard covers the whole
    # register (an entry only one claim declares would else leave its group's register with it). Let through, each
    # for the reason given:
    unused = {cid: set() for cid in DEPENDS}
    # the two manoeuvres differ from 2 s after the onset on, beyond C001-2's runs (they end roc_delay_s <= 1 s after it)
    unused["C001-2"] |= {"manoeuvre"}
    # C001-3 reads of the scenario only its frame rate and onset, which the motion of either channel leaves as they are
    unused["C001-3"] |= {"accel_unit", "channel_y", "manoeuvre"}
    # the curves are computed on channel x alone; the scenario builds channel y's motion with it
    unused["C001-7"] |= {"channel_y"}
    unused["C001-8"] |= {"channel_y"}
    depends = {cid: [*names, *sorted(unused[cid] - set(names))] for cid, names in DEPENDS.items()}
    return [(functools.partial(fn, sizes=sizes), reg, depends, list(GROUPS[g])) for g, fn in fns.items()]


def _p002():
    from tvtrack.papers.p002_unified_location_em import study
    from tvtrack.papers.p002_unified_location_em.register import DEPENDS, REGISTER

    scale = study.Scale(
        n_trials=2,
        n_iter_trials=2,
        separations=(1.0, 2.0, 3.0, 4.0, 6.0, 8.0),
        fig3_frames=(5, 10, 50),
        crb_phases=1,
        n_bootstrap=20,
        max_iter=20,
    )
    return [(functools.partial(study.measure, scale=scale), REGISTER, DEPENDS, list(DEPENDS))]


def _p003():
    from tvtrack.papers.p003_rotating_marker_tracker import study
    from tvtrack.papers.p003_rotating_marker_tracker.register import DEPENDS, REGISTER

    sizes = study.Sizes(trials=2, fig1_s=0.6, fig2_s=0.5, transient_s=0.1, horizon_s=0.3)
    tracking = ["C003-1", "C003-2", "C003-3", "C003-4", "C003-9"]
    interference = ["C003-5", "C003-6", "C003-7", "C003-10", "C003-11", "C003-12"]
    # both measurements project each claim's configuration onto its DEPENDS (tvtrack.projection.as_declared), so
    # the guard watches them beneath the decorator, over the whole register; there one function builds the scenes
    # of both studies and reads every scene entry. Let through, each for the reason given (each checked not to move
    # the claim's value at these sizes once the scene draws nothing for interferers it does not have):
    unused = {cid: set() for cid in DEPENDS}
    interferers = {"interferer_layout", "interferer_radius", "interferer_size", "placement", "horizon"}
    for cid in tracking:
        unused[cid] |= interferers | {"decoy_brightness"}  # the tracking scenes have no interferer, decoy or horizon
    for cid in ("C003-1", "C003-2", "C003-4", "C003-9"):
        unused[cid] |= {"fig2_law"}  # the Fig. 2 scene is set up for every tracking claim; only C003-3 runs it
    for cid in ("C003-1", "C003-2", "C003-3", "C003-4"):
        unused[cid] |= {"edge_norm"}  # the edge discriminator's normalisation: only C003-9's edge-form runs use it
    unused["C003-3"] |= {"rotation_rate", "loss_window_s", "loss_radius"}  # Fig. 2's own law; no run counted lost
    unused["C003-4"] |= {"residual_background"}  # the background sweep sets the residual itself
    unused["C003-9"] |= {"spot"}  # C003-9 runs both spots: the entry only says which one the Fig. 1 batch gives
    for cid in interference:
        unused[cid] |= {"edge_norm"}  # the interference runs use the quadrant discriminator
    for cid in ("C003-5", "C003-6", "C003-7", "C003-10", "C003-11"):
        unused[cid] |= {"static_gate", "decoy_brightness"}  # the static marker and the decoy: C003-12's curves only
    for cid in ("C003-5", "C003-6", "C003-7", "C003-10", "C003-12"):
        # the scenes read the discriminator's bandwidth reading; these claims leave it at its default for cost
        # (docs/validity/003.md): it does not move them at these sizes; C003-11, which it moves, declares it
        unused[cid] |= {"bandwidth_reading"}
    depends = {cid: [*names, *sorted(unused[cid] - set(names))] for cid, names in DEPENDS.items()}
    return [
        (functools.partial(study.measure_tracking.__wrapped__, sizes=sizes), REGISTER, depends, tracking),
        (functools.partial(study.measure_interference.__wrapped__, sizes=sizes), REGISTER, depends, interference),
    ]


def _p004():
    from tvtrack.papers.p004_laser_spot_prediction import REGISTER, study
    from tvtrack.papers.p004_laser_spot_prediction.register import DEPENDS, WORLD

    size = study.StudySize(
        n_paths=3,
        n_frames=120,
        floor_grid=(5, 10),
        window_grid=(4, 10),
        mlp_hidden_units=4,
        rbf_centres=8,
        train_samples=100,
        n_mc_variance=200,
        timing_frames=10,
    )
    # study.measure projects each claim's configuration onto its DEPENDS (tvtrack.projection.as_declared): an entry
    # the claim does not declare reaches it as the register's default, never as the guard's stand-in, so the guard
    # watches the measurement beneath the projection, asked for the one claim at the same configuration. There it
    # also sees entries read for every claim whose values only other claims use; these alone are let through:
    used_by = {"lost frames": "C004-4", "spline": "C004-3", "network lags": "C004-3b"}
    unused = {cid: {e for e, user in used_by.items() if user != cid} for cid in DEPENDS}
    # the scene is rendered before the claims are read: C004-5 uses none of it, C004-8 times the per-frame work of
    # the camera (read noise, saturation, energy centre) at the frame rate, not the paths or the spot's size
    unused["C004-5"] |= set(WORLD)
    unused["C004-8"] |= set(WORLD) - {"frame rate", "read noise", "saturation", "energy centre"}
    # the scene's world is calibrated at the horizon read (operating.OPERATING_READINGS): it reads the horizon for
    # every claim; a claim that does not declare it gets the default's, so its world is the one-frame world
    for cid in ("C004-4", "C004-5", "C004-8"):
        unused[cid] |= {"horizon"}
    depends = {cid: [*names, *sorted(unused[cid] - set(names))] for cid, names in DEPENDS.items()}
    return [(functools.partial(study.measure.__wrapped__, size=size), REGISTER, depends, list(DEPENDS))]


#: Per paper package: ``[(measure on small sizes, the register it is explored over, DEPENDS, its claims)]``, as
#: the notebook calls the explorer.
MEASUREMENTS = {
    "p000_dissector_ekf": _p000,
    "p001_maneuver_occlusion_kf": _p001,
    "p002_unified_location_em": _p002,
    "p003_rotating_marker_tracker": _p003,
    "p004_laser_spot_prediction": _p004,
}


def test_every_paper_package_has_its_measurements_here():
    assert sorted(MEASUREMENTS) == PACKAGES


#: Entries a claim's measurement reads, whose value changes the claim's, but that its ``DEPENDS`` does not declare
#: (so the exploration never varies them for it): open until the register declares them (or the measurement stops
#: reading them). The paper's check lets them through, then checks that each is still read and marks the paper an
#: expected failure naming them.
UNDECLARED_READS: dict[str, dict[str, tuple[str, ...]]] = {}


class UndeclaredReads(AssertionError):
    """The reads of :data:`UNDECLARED_READS` are still there (and nothing else undeclared is read)."""


def _gap_marks(name):
    gaps = UNDECLARED_READS.get(name)
    if not gaps:
        return name
    said = "; ".join(f"{cid} reads {', '.join(entries)}" for cid, entries in gaps.items())
    why = f"{name}: claims read entries they do not declare (DEPENDS): {said}"
    return pytest.param(name, marks=pytest.mark.xfail(strict=True, raises=UndeclaredReads, reason=why))


@pytest.mark.parametrize("name", [_gap_marks(n) for n in PACKAGES])
def test_every_claim_reads_only_the_entries_it_declares(name):
    if name not in MEASUREMENTS:
        pytest.fail(f"{name}: add its measurements to MEASUREMENTS")
    gaps = UNDECLARED_READS.get(name, {})
    violations, still = {}, {}
    for measure, register, depends, claims in MEASUREMENTS[name]():
        known = {cid: [*names, *sorted(set(gaps.get(cid, ())) - set(names))] for cid, names in depends.items()}
        violations.update(check_declared(measure, register, known, 3, claims))
        open_ = [cid for cid in claims if set(gaps.get(cid, ())) - set(depends[cid])]
        still.update(check_declared(measure, register, depends, 3, open_))
    short = {cid: re.sub(r": add it to DEPENDS.*", "", msg) for cid, msg in violations.items()}
    assert not short, f"{name}: claims read undeclared entries: {short}"
    if still:
        left = {cid: re.sub(r": add it to DEPENDS.*", "", msg) for cid, msg in still.items()}
        raise UndeclaredReads(f"{name}: claims still read entries they do not declare: {left}")
