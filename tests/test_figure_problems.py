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
    assert _drawn(fig) == ["gate: colours mapped from values without a colour bar saying what they are"]
    cb = fig.colorbar(im, ax=axs[0])
    assert _drawn(fig) == [
        "gate: colours mapped from values without a colour bar saying what they are"
    ]  # a bar, no label
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


def test_log_ticks_hidden_axes_meshes_and_insets_are_read_as_a_reader_sees_them():
    """A log axis reaching below 1 (ticks 10^{-1}) is numeric; a hidden axis needs no label; a colour-mapped mesh
    needs a labelled colour bar, a contour line of one colour does not; an inset is a panel too."""
    fig, ax = plt.subplots()
    ax.plot([1, 2, 3], [1e-3, 1e-2, 1e-1])
    ax.set_yscale("log")
    ax.set_xlabel("x (s)")
    assert _drawn(fig) == ["panel 1: its y axis has no label"]
    ax.yaxis.set_visible(False)
    assert _drawn(fig) == []
    fig, ax = plt.subplots()
    ax.contour(np.arange(5), np.arange(5), np.eye(5), levels=[0.5], colors="c")
    ax.set(xlabel="x (px)", ylabel="y (px)")
    assert _drawn(fig) == []
    mesh = ax.pcolormesh(np.arange(16.0).reshape(4, 4))
    assert _drawn(fig) == ["panel 1: colours mapped from values without a colour bar saying what they are"]
    fig.colorbar(mesh, ax=ax).ax.set_title("DN")
    assert _drawn(fig) == []
    inset = ax.inset_axes([0.6, 0.6, 0.3, 0.3])
    inset.plot([1, 2], [3, 4])
    inset.set_title("zoom")
    assert _drawn(fig) == ["zoom: its x axis has no label", "zoom: its y axis has no label"]
    plt.close("all")


def test_a_numpy_string_or_truth_value_reads_as_itself():
    from tvtrack.numbers import number, setting

    assert setting("mode", np.str_("fast")) == "mode = fast" and setting("known", np.bool_(True)) == "known = True"
    assert number(np.bool_(False)) == "False" and number(np.float64(5 / 3)) == "1.667"
