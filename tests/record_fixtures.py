"""Claim records in the schema of the explorer's robustness record (share, flips, sensitivity, runs to decide,
register phrases), for the report, site and wording tests. Names mimic real ones (C001-3, C001-7, C004-3b) so the
tests read like the runs they stand for; the register keys have underscores so code forms are easy to spot."""

from __future__ import annotations

import copy

REGISTER = [
    {
        "name": "paper_sigma",
        "kind": "reading",
        "default": "filtered",
        "values": ["filtered", "raw_increments"],
        "why": "the text says 'sigma' without saying of what",
        "origin": "author",
        "title": "what the paper's sigma is the SD of",
        "side": "reading",
        "phrases": {
            "filtered": "sigma read as the SD of the filtered velocity",
            "raw_increments": "sigma read as the SD of the raw velocity increments",
        },
    },
    {
        "name": "k_bound2",
        "kind": "reading",
        "default": 40,
        "values": [40, 100],
        "why": "Fig. 4 shows three curves without their frames",
        "origin": "author",
        "title": "frame at which the gain bound is set",
        "side": "reading",
        "phrases": {"40": "gain bound set at frame 40", "100": "gain bound set at frame 100"},
    },
    {
        "name": "target_motion",
        "kind": "regime",
        "default": "straight",
        "values": ["straight", "weave"],
        "why": "the paper simulates one straight pass",
        "origin": "author",
        "title": "how the target moves",
        "side": "world",
        "phrases": {"straight": "a target on a straight pass", "weave": "a target weaving at 0.1 T"},
    },
]


def _est(v, lo, hi, n=400):
    return {"value": v, "se": (hi - lo) / 3.92, "ci_low": lo, "ci_high": hi, "n": n}


def _share(agree, decided, design, lo, hi):
    """The share record: agree, flip and undecided over every explored configuration; value = agree / design."""
    return {
        "agree": agree,
        "flip": decided - agree,
        "decided": decided,
        "undecided": design - decided,
        "design": design,
        "value": agree / design,
        "ci_low": lo,
        "ci_high": hi,
    }


def _conditions(values, verdicts, changed):
    return [
        {"changed": ch, "kind": kind, "measured": m, "verdict": v, "parts": {"claim": v}, "text": ""}
        for (ch, kind), m, v in zip(changed, values, verdicts)
    ]


_CHANGED = [
    ({"paper_sigma": "raw_increments"}, "single"),
    ({"k_bound2": 100}, "single"),
    ({"target_motion": "weave"}, "single"),
    ({"paper_sigma": "raw_increments", "target_motion": "weave"}, "joint"),
    ({"k_bound2": 100, "target_motion": "weave"}, "joint"),
    ({"paper_sigma": "raw_increments", "k_bound2": 100}, "combination"),
]

#: Not reproduced, depends: a reading (sigma) flips it and a world (weave) too; a false-alarm rate in x alpha.
DEPENDS = {
    "id": "C001-3",
    "statement": "Neighbouring velocity samples correlate by <= 0.5, negligibly; the pair distributions may be multiplied.",
    "paper_value": "rho <= 0.5",
    "rule": {
        "kind": "in_band",
        "text": "per-test false-alarm rate / alpha in [0, 2]",
        "quantity": "per-test false-alarm rate / alpha",
        "low": 0.0,
        "high": 2.0,
        "unit": "x alpha",
        "better": None,
    },
    "acceptance": "per-test false-alarm rate / alpha in [0, 2]",
    "measured": _est(351.6, 350.0, 353.1),
    "verdict": "not reproduced",
    "decision": "per-test false-alarm rate / alpha = 351.6 lies wholly above the band",
    "note": "the two windows overlap",
    "robustness": {
        "label": "depends",
        "provisional": False,
        "where": ["reproduced when paper_sigma = raw_increments; target_motion = weave"],
        "coverage": "depends over 38 conditions x 3 independent replicates",
        "parts": {
            "claim": {
                "verdict": "not reproduced",
                "label": "depends",
                "replicate_verdicts": ["not reproduced"] * 3,
                "runs_to_decide": None,
                "share": _share(29, 32, 32, 0.75, 0.98),
                "flips": [
                    {
                        "changed": {"paper_sigma": "raw_increments"},
                        "side": "reading",
                        "kind": "single",
                        "verdict": "reproduced",
                        "text": "sigma read as the SD of the raw velocity increments",
                    },
                    {
                        "changed": {"target_motion": "weave"},
                        "side": "world",
                        "kind": "single",
                        "verdict": "reproduced",
                        "text": "a target weaving at 0.1 T",
                    },
                ],
                "sensitivity": [
                    {"entry": "paper_sigma", "title": "what the paper's sigma is the SD of", "score": 0.81},
                    {"entry": "target_motion", "title": "how the target moves", "score": 0.12},
                ],
            }
        },
        "replicates": [
            {"seed": s, "measured": _est(351 + s / 10, 349.0, 354.0), "verdict": "not reproduced"} for s in (1, 2, 3)
        ],
        "conditions": _conditions(
            [
                _est(1.2, 1.0, 1.4),
                _est(340.0, 338.0, 342.0),
                _est(1.8, 1.5, 1.9),
                _est(0.9, 0.8, 1.0),
                _est(2.5, 2.2, 2.9),
                _est(1.1, 1.0, 1.3),
            ],
            ["reproduced", "not reproduced", "reproduced", "reproduced", "not reproduced", "reproduced"],
            _CHANGED,
        ),
        "register": copy.deepcopy(REGISTER),
        "design": {"joint": 32, "replicates": 3},
    },
}

#: Undecided: the interval straddles the band's edge; runs_to_decide says how many would decide it.
UNDECIDED = copy.deepcopy(DEPENDS) | {
    "id": "C004-3b",
    "statement": "The filter is more accurate than back-propagation networks (2-3 px).",
    "paper_value": "filter 1-2 px; MLP 2-3 px",
    "rule": {
        "kind": "in_band",
        "text": "MSE ratio network / filter in [0, 0.625]",
        "quantity": "MSE ratio network / filter",
        "low": 0.0,
        "high": 0.625,
        "unit": "ratio of MSEs, network / filter",
    },
    "acceptance": "MSE ratio network / filter in [0, 0.625]",
    "measured": _est(0.6209, 0.6162, 0.6256),
    "verdict": "undecided",
}
UNDECIDED["robustness"]["label"] = "unexplored"
UNDECIDED["robustness"]["parts"]["claim"].update(
    verdict="undecided",
    label="-",
    flips=[],
    share=None,
    runs_to_decide={"replicates": 7, "now": 3, "text": "about 7 replicates (560 trials) would decide it"},
)

#: Reproduced, deterministic, a long vector (a monotone trend) with zero-width intervals.
VECTOR = {
    "id": "C001-7",
    "statement": "Manoeuvre-induced dynamic errors substantially affect the prediction if the object is lost early.",
    "paper_value": "qualitative",
    "rule": {
        "kind": "all_of",
        "text": "all of: decreasing; dominates early",
        "parts": {
            "decreasing": {
                "kind": "monotone",
                "text": "dynamic error is decreasing in the loss frame",
                "quantity": "dynamic error",
                "over": "the loss frame",
                "direction": "decreasing",
                "unit": "px",
            },
            "dominates early": {
                "kind": "in_band",
                "text": "dynamic / random error at least 1",
                "quantity": "dynamic / random error",
                "low": 1.0,
                "high": None,
                "unit": "ratio of RMS errors, dynamic / random",
            },
        },
    },
    "acceptance": "all of: decreasing; dominates early",
    "measured": {
        "decreasing": [_est(v, v, v, 1) for v in (2.163e5, 7839.0, 2055.0, 738.8, 201.0, 83.93, 39.91, 12.31, 0.178)],
        "dominates early": _est(13.14, 13.14, 13.14, 1),
    },
    "verdict": "reproduced",
    "decision": "",
    "note": "",
    "robustness": {
        "label": "limited",
        "provisional": False,
        "where": [],
        "coverage": "limited over 6 conditions; deterministic",
        "parts": {
            "decreasing": {
                "verdict": "reproduced",
                "label": "robust",
                "replicate_verdicts": [],
                "runs_to_decide": None,
                "share": _share(32, 32, 32, 0.89, 1.0),
                "flips": [],
                "sensitivity": [],
            },
            "dominates early": {
                "verdict": "reproduced",
                "label": "limited",
                "replicate_verdicts": [],
                "runs_to_decide": None,
                "share": _share(24, 32, 32, 0.57, 0.89),
                "flips": [
                    {
                        "changed": {"target_motion": "weave"},
                        "side": "world",
                        "kind": "single",
                        "verdict": "not reproduced",
                        "text": "a target weaving at 0.1 T",
                    }
                ],
                "sensitivity": [],
            },
        },
        "replicates": [],
        "conditions": [
            {
                "changed": ch,
                "kind": kind,
                "measured": {
                    "decreasing": [_est(9.0 - k, 9.0 - k, 9.0 - k, 1) for k in range(3)],
                    "dominates early": _est(0.5 + i, 0.5 + i, 0.5 + i, 1),
                },
                "verdict": "partly" if i == 0 else "reproduced",
                "parts": {"decreasing": "reproduced", "dominates early": "not reproduced" if i == 0 else "reproduced"},
                "text": "",
            }
            for i, (ch, kind) in enumerate(_CHANGED)
        ],
        "register": copy.deepcopy(REGISTER),
        "design": {"joint": 32, "replicates": 0},
    },
}

#: A smoke-size run: the record says robust, but its design is too small to label.
SMOKE = copy.deepcopy(DEPENDS) | {"id": "C001-5", "verdict": "reproduced", "measured": _est(1.2, 1.0, 1.4)}
SMOKE["robustness"].update(label="robust", provisional=True)
SMOKE["robustness"]["parts"]["claim"].update(verdict="reproduced", label="robust", flips=[], share=None)

NOT_CHECKABLE = {
    "id": "C001-6",
    "statement": "The paper's Fig. 5 shows the tracking of a real aircraft.",
    "paper_value": "a figure",
    "rule": {"kind": "not_checkable", "text": "not checkable: no data", "reason": "no data"},
    "acceptance": "not checkable: no data",
    "measured": None,
    "verdict": "not checkable",
    "decision": "",
    "note": "the recording of the real aircraft is not published",
    "robustness": None,
}

CLAIMS = [DEPENDS, UNDECIDED, VECTOR, SMOKE, NOT_CHECKABLE]
REGISTER_KEYS = [e["name"] for e in REGISTER]
