"""A share in words (:func:`tvtrack.numbers.percent`): whole per cent, and a rare event never reads as absent."""

import pytest

from tvtrack.numbers import percent


@pytest.mark.parametrize(
    ("share", "text"),
    [
        (0.0, "0%"),
        (1.0, "100%"),
        (0.38, "38%"),
        (0.004, "<1%"),
        (1 / 480, "<1%"),
        (0.005, "<1%"),
        (0.996, ">99%"),
        (0.994, "99%"),
        (0.5, "50%"),
    ],
)
def test_a_share_in_whole_per_cent_never_rounds_a_rare_event_away(share, text):
    assert percent(share) == text
