"""Kernels that start under load: the runner's kernels use ipc sockets (no TCP port to race
for), run this environment's Python whatever kernel specs are installed, print to the run's kernel.log and
never to the terminal, and many started at once all succeed. The clone's JupyterLab kernel is its own."""

import json
import socket
import sys
from pathlib import Path

import pytest

from conftest import FIXTURE_NOTEBOOK
from tvtrack.pipeline.runner import run_notebook

TINY = {"n_trials": 5, "n_frames": 3, "rerun_mode": "off"}


def test_a_tcp_port_taken_between_its_choice_and_the_kernels_bind_cannot_kill_a_run(tmp_path, monkeypatch):
    """The race of TCP kernels started by separate processes, made certain: every port the parent picks is
    already bound by someone else when the kernel binds it ("ZMQError: Address already in use")."""
    from jupyter_client.provisioning import local_provisioner

    taken = socket.socket()
    taken.bind(("127.0.0.1", 0))
    taken.listen(1)
    port = taken.getsockname()[1]
    monkeypatch.setattr(local_provisioner.LocalPortCache, "find_available_port", lambda self, ip: port)
    try:
        outcome = run_notebook(FIXTURE_NOTEBOOK, tmp_path / "run", TINY)
    finally:
        taken.close()
    assert outcome.ok, outcome.error


def test_a_kernel_that_dies_at_start_is_one_line_and_its_traceback_stays_in_kernel_log(tmp_path, monkeypatch, capfd):
    broken = tmp_path / "broken"
    broken.mkdir()
    (broken / "ipykernel_launcher.py").write_text("raise ImportError('planted: this kernel cannot start')\n")
    monkeypatch.setenv("PYTHONPATH", f"{broken}:{Path(__file__).parents[1] / 'lib'}")
    outcome = run_notebook(FIXTURE_NOTEBOOK, tmp_path / "run", TINY)
    out, err = capfd.readouterr()
    assert out + err == ""  # no traceback, no kernel line, no papermill line
    assert outcome.status == "failed" and "\n" not in outcome.error
    assert "kernel died before it answered (3 attempts)" in outcome.error
    log = (tmp_path / "run" / "kernel.log").read_text()
    assert log.count("ImportError: planted: this kernel cannot start") == 3  # started again twice, then given up
    assert log.count("starting another") == 2


def test_the_runner_ignores_a_python3_kernel_spec_of_another_environment(tmp_path, monkeypatch):
    """A per-user ``python3`` spec found first (here through JUPYTER_PATH) must not be what the runner starts."""
    spec = tmp_path / "jupyter" / "kernels" / "python3"
    spec.mkdir(parents=True)
    (spec / "kernel.json").write_text(
        json.dumps({"argv": ["/bin/false", "{connection_file}"], "display_name": "Other", "language": "python"})
    )
    monkeypatch.setenv("JUPYTER_PATH", str(tmp_path / "jupyter"))
    monkeypatch.delenv("TVTRACK_KERNEL", raising=False)
    outcome = run_notebook(FIXTURE_NOTEBOOK, tmp_path / "run", TINY)
    assert outcome.ok, outcome.error
    assert not (tmp_path / "run" / "kernel.log").exists()  # nothing printed: the empty log is not kept


def test_eight_kernels_starting_at_once_all_start_and_succeed(tmp_path):
    """Eight runs on eight jobs: every kernel starts at the same moment (the start race of a loaded machine)."""
    from tvtrack.pipeline.sweep import run_sweep

    spec = tmp_path / "many.toml"
    spec.write_text(
        f'notebook = "{FIXTURE_NOTEBOOK}"\nrepeats = 2\n[fixed]\nn_trials = 2\nn_frames = 2\nrerun_mode = "off"\n'
        "[grid]\nspot_sigma_px = [1.0, 1.5, 2.0, 3.0]\n"
    )
    s = run_sweep(spec, jobs=8, output=tmp_path / "many", progress=False)
    rows = s.summary_csv.read_text().splitlines()[1:]
    assert (s.n_runs, s.n_ok, s.n_failed) == (8, 8, 0), rows
    assert not list((tmp_path / "many" / "runs").glob(".tmp-*"))


def test_each_clone_has_its_own_kernel_in_its_own_environment(tmp_path):
    from tvtrack.pipeline.kernels import clone_kernel_name, install_clone_kernel
    from tvtrack.pipeline.paths import REPO_ROOT

    a, b = tmp_path / "clone-a" / "tvtrack-repro", tmp_path / "clone-b" / "tvtrack-repro"
    assert clone_kernel_name(a) != clone_kernel_name(b) and clone_kernel_name(a) == clone_kernel_name(a)
    assert clone_kernel_name(a).startswith("tvtrack-repro-")
    spec_a = install_clone_kernel(prefix=tmp_path / "venv-a", root=a)
    before = (spec_a / "kernel.json").read_text()
    spec_b = install_clone_kernel(prefix=tmp_path / "venv-b", root=b)
    assert (spec_a / "kernel.json").read_text() == before  # installing clone b leaves clone a's kernel alone
    assert spec_a == tmp_path / "venv-a" / "share" / "jupyter" / "kernels" / clone_kernel_name(a)
    for path, root in ((spec_a, a), (spec_b, b)):
        kernel = json.loads((path / "kernel.json").read_text())
        assert kernel["argv"][0] == sys.executable
        assert kernel["env"] == {"RERUN_NOTEBOOK_ASSET": "inline"}
        assert str(root.parent) in kernel["display_name"]
    # make kernel installs into the clone's environment, never per user
    makefile = (REPO_ROOT / "Makefile").read_text()
    target = makefile.split("\nkernel:")[1].split("\n\n")[0]
    assert "tvtrack.pipeline.kernels" in target and "--user" not in target


@pytest.mark.parametrize("name", ["python3"])
def test_the_runner_names_a_kernel_spec_only_through_tvtrack_kernel(name, monkeypatch, tmp_path):
    from tvtrack.pipeline.kernels import KernelSetup

    monkeypatch.delenv("TVTRACK_KERNEL", raising=False)
    with KernelSetup(tmp_path / "k.log") as setup:
        assert setup.kernel_name == name and setup.named is None
        km = setup.manager_class()(kernel_name=setup.kernel_name)
        assert km.transport == "ipc" and len(km.ip) < 100
    monkeypatch.setenv("TVTRACK_KERNEL", "my-kernel")
    with KernelSetup(tmp_path / "k2.log") as setup:
        assert setup.kernel_name == "my-kernel"


def test_a_kernel_log_with_only_the_shutdown_interrupt_line_is_not_kept(tmp_path):
    """jupyter_client interrupts every kernel at shutdown; on a loaded machine ipykernel may log it. That line
    alone is no reason to keep a log; any other line is."""
    from tvtrack.pipeline.runner import SHUTDOWN_CHATTER, drop_quiet_log

    quiet, empty, loud = tmp_path / "quiet.log", tmp_path / "empty.log", tmp_path / "loud.log"
    quiet.write_text(SHUTDOWN_CHATTER + "\n")
    empty.write_text("")
    loud.write_text(SHUTDOWN_CHATTER + "\nTraceback (most recent call last):\n")
    assert drop_quiet_log(quiet) and not quiet.exists()
    assert drop_quiet_log(empty) and not empty.exists()
    assert not drop_quiet_log(loud) and loud.exists()
    assert not drop_quiet_log(tmp_path / "absent.log")
