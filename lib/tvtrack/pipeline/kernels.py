"""The Jupyter kernels of this clone: the ones the runner starts, and the one JupyterLab offers.

Kernels the runner starts (:class:`KernelSetup`)
    * talk to the runner over ``ipc`` (Unix sockets in a private folder), not TCP. A TCP kernel's ports are
      chosen by the parent (bind port 0, close) and bound again by the kernel a moment later, so kernels
      started at the same moment by separate processes (a sweep's pool workers, two sweeps) can pick the
      same port and die with "ZMQError: Address already in use". A socket path of our own cannot collide.
    * run this environment's Python (``sys.executable -m ipykernel_launcher``) unless ``TVTRACK_KERNEL``
      names an installed kernel spec: the runner never depends on which ``python3`` spec Jupyter finds first.
    * print to ``kernel.log`` in the run's folder, never to the user's terminal (a kernel that fails to
      start prints a traceback there).

The clone's kernel for JupyterLab (:func:`install_clone_kernel`, ``make kernel``)
    is installed into the clone's virtual environment (``.venv/share/jupyter/kernels``), where the
    environment's own ``jupyter lab`` (``make edit``) finds it, under a name of its own
    (:func:`clone_kernel_name`: ``tvtrack-repro-`` and a digest of the clone's path), so two clones on one
    account never repoint each other's kernel. The working copies of ``make edit`` name that kernel.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import logging
import os
import shutil
import sys
import tempfile
from pathlib import Path

from .paths import REPO_ROOT

__all__ = ["KernelSetup", "check_kernel_variable", "clone_kernel_name", "install_clone_kernel", "IPC_PATH_MAX"]

IPC_PATH_MAX = 90
"""Longest socket path prefix used (Unix socket paths are limited to 107 bytes; ``-N`` is appended)."""


def _ipc_parent() -> str:
    """A temporary folder whose paths stay short enough for Unix sockets."""
    tmp = tempfile.gettempdir()
    return tmp if len(tmp) < IPC_PATH_MAX - 30 else "/tmp"


class KernelSetup:
    """What the runner's kernels need for one run, as a context manager.

    Parameters
    ----------
    log_path : Path
        File that receives the kernels' stdout and stderr (appended).
    kernel_name : str or None
        An installed kernel spec, or ``None``: this environment's Python (or ``TVTRACK_KERNEL``).
    """

    def __init__(self, log_path: Path, kernel_name: str | None = None):
        self.log_path = Path(log_path)
        self.named = kernel_name or os.environ.get("TVTRACK_KERNEL")
        self.kernel_name = self.named or "python3"
        self._attempt = 0
        self._dir: str | None = None
        self._log = None

    def __enter__(self) -> "KernelSetup":
        self._dir = tempfile.mkdtemp(prefix="tvk-", dir=_ipc_parent())
        self._log = open(self.log_path, "ab")  # noqa: SIM115 - closed in __exit__
        # papermill's own lines about a kernel ("Error occurred while starting new kernel client ...") go to
        # the same log, not to the terminal (Python's last-resort handler prints unhandled warnings there)
        self._handler = _LogHandler(self)
        self._logger = logging.getLogger("papermill")
        self._propagate = self._logger.propagate
        self._logger.addHandler(self._handler)
        self._logger.propagate = False
        return self

    def __exit__(self, *exc) -> None:
        self._logger.removeHandler(self._handler)
        self._logger.propagate = self._propagate
        if self._log is not None:
            self._log.close()
        if self._dir:
            shutil.rmtree(self._dir, ignore_errors=True)

    def note(self, text: str) -> None:
        """A line of the runner's own in the kernel log (e.g. a start that is tried again)."""
        self._log.write((text + "\n").encode())
        self._log.flush()

    def manager_class(self):
        """A kernel manager class for one kernel start: ipc sockets of its own, output to the log."""
        from jupyter_client import AsyncKernelManager

        self._attempt += 1
        ip = os.path.join(self._dir, f"k{self._attempt}")
        log, pinned = self._log, self.named is None

        class RunKernelManager(AsyncKernelManager):
            def __init__(self, **kw):
                super().__init__(**kw)
                self.transport = "ipc"
                self.ip = ip

            def format_kernel_cmd(self, extra_arguments=None):
                if not pinned:
                    return super().format_kernel_cmd(extra_arguments)
                connection = os.path.realpath(self.connection_file)
                return [sys.executable, "-m", "ipykernel_launcher", "-f", connection, *(extra_arguments or [])]

            async def _async_launch_kernel(self, kernel_cmd, **kw):
                kw["stdout"] = kw["stderr"] = log
                return await super()._async_launch_kernel(kernel_cmd, **kw)

        return RunKernelManager


def check_kernel_variable() -> None:
    """Refuse a ``TVTRACK_KERNEL`` that names no installed kernel spec, before any run starts.

    Raises
    ------
    UsageError
        One line naming the variable, its value and the kernel specs installed.
    """
    name = os.environ.get("TVTRACK_KERNEL")
    if not name:
        return
    from jupyter_client.kernelspec import KernelSpecManager

    from .preflight import UsageError

    installed = sorted(KernelSpecManager().find_kernel_specs())
    if name.lower() not in installed:  # jupyter_client looks kernel specs up in lower case
        raise UsageError(
            f"TVTRACK_KERNEL={name!r} names no installed kernel spec; installed: {', '.join(installed) or 'none'} "
            "(or unset TVTRACK_KERNEL: the runner then starts this environment's Python)"
        )


class _LogHandler(logging.Handler):
    """Records of papermill's logger, as lines of the kernel log."""

    def __init__(self, setup: KernelSetup):
        super().__init__(logging.WARNING)
        self.setup = setup

    def emit(self, record: logging.LogRecord) -> None:
        with contextlib.suppress(Exception):
            self.setup.note(f"papermill: {record.getMessage()}")


def clone_kernel_name(root: str | Path = REPO_ROOT) -> str:
    """``tvtrack-repro-<8 hex digits of the clone's resolved path>``: one name per clone."""
    digest = hashlib.sha256(str(Path(root).resolve()).encode()).hexdigest()[:8]
    return f"tvtrack-repro-{digest}"


def install_clone_kernel(prefix: str | Path = sys.prefix, root: str | Path = REPO_ROOT) -> Path:
    """Install the clone's kernel spec into ``prefix`` (default: this virtual environment), running this
    Python, with ``RERUN_NOTEBOOK_ASSET=inline`` (the notebook viewer from the installed package, offline).

    Returns
    -------
    Path
        The kernel spec's folder, ``<prefix>/share/jupyter/kernels/<clone_kernel_name(root)>``.
    """
    from ipykernel.kernelspec import install

    root = Path(root).resolve()
    with contextlib.redirect_stdout(io.StringIO()):  # ipykernel's own 'Installed kernelspec' line
        path = install(
            kernel_name=clone_kernel_name(root),
            display_name=f"Python (tvtrack-repro, {root.name} at {root.parent})",
            prefix=str(prefix),
            env={"RERUN_NOTEBOOK_ASSET": "inline"},
        )
    return Path(path)


if __name__ == "__main__":  # make kernel
    print(f"installed the kernel {clone_kernel_name()} in {install_clone_kernel()}")
