"""``tvtrack.figure_checks.figure_problems``: what a reader would miss in a figure (a numeric axis without a label, an
image without a colour bar saying its values and unit), recorded beside the figure by ``Results.save_figure``."""

import io
import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from tvtrack.figure_checks import figure_problems  # noqa: E402
from tvtrack.results import Results  # noqa: E402


def _drawn(fig):
    fig.savefig(io.BytesIO())
    return figure_problems(fig)


def test_a_numeric_axis_needs_a_label_and_text_ticks_or_a_shared_labelled_axis_do_not():
    fig, axs = plt.subplots(3, 1, sharex=True)
    axs[0].plot([1, 2], [3, 4])
    axs[0].set_ylabel("error (px)")
    axs[1].semilogy([1, 2], [10, 1000])  # log ticks are mathtext: still numbers
    axs[1].set_title("(b) spread")
    axs[2].bar(["ULA", "two-stage"], [1, 2])  # x: text ticks; shares x with the others, which have no label
    axs[2].set_ylabel("variance (sigma^2)")
    assert _drawn(fig) == ["(b) spread: its y axis has no label"]
    axs[1].set_ylabel("variance (px^2)")
    assert _drawn(fig) == []  # the bars' text ticks need no label, and x is shared with them
    fig, ax = plt.subplots()
    ax.plot([1, 2], [3, 4])
    assert _drawn(fig) == ["panel 1: its x axis has no label", "panel 1: its y axis has no label"]
    plt.close("all")


def test_an_image_needs_a_labelled_colour_bar_and_an_rgb_picture_does_not():
    fig, axs = plt.subplots(1, 2)
    im = axs[0].imshow(np.eye(4))
    axs[0].set(xlabel="x (px)", ylabel="y (px)", title="gate")
    axs[1].imshow(np.ones((4, 4, 3)))
    axs[1].set(xlabel="x (px)", ylabel="y (px)")
    assert _drawn(fig) == ["gate: an image without a colour bar saying its values and unit"]
    cb = fig.colorbar(im, ax=axs[0])
    assert _drawn(fig) == ["gate: an image without a colour bar saying its values and unit"]  # a bar, no label
    cb.set_label("pixel value (DN)")
    assert _drawn(fig) == []
    plt.close("all")


def test_save_figure_records_the_problems_beside_the_figure_and_nothing_for_a_good_one(tmp_path):
    res = Results(notebook="t", citation="c", parameters={"seed": 1, "output_dir": str(tmp_path)})
    fig, ax = plt.subplots()
    ax.plot([1, 2], [3, 4])
    ax.set_xlabel("time (s)")
    res.save_figure(fig, "bad", "A curve.")
    fig, ax = plt.subplots()
    ax.plot([1, 2], [3, 4])
    ax.set(xlabel="time (s)", ylabel="error (px)")
    res.save_figure(fig, "good", "A curve.")
    res.write()
    figures = json.loads((tmp_path / "results.json").read_text())["figures"]
    assert figures == [
        {"file": "bad.png", "caption": "A curve.", "problems": ["panel 1: its y axis has no label"]},
        {"file": "good.png", "caption": "A curve."},
    ]
