"""Whether the headless Rerun viewer can run here, and the tools around it: the Vulkan driver check,
the ``rerun`` command of this environment, ``rerun rrd verify`` and a free local port.

The native viewer renders through Vulkan; on a machine without a GPU it runs on Mesa's software
rasteriser (llvmpipe, package ``mesa-vulkan-drivers``). Without any Vulkan driver it cannot start,
and :class:`ViewerUnavailable` says which package to install. Re-exported by :mod:`tvtrack.pipeline.viewer`.
"""

from __future__ import annotations

import ctypes
import glob
import os
import shutil
import socket
import subprocess
import sys
from pathlib import Path

__all__ = ["INSTALL_HINT", "ViewerUnavailable", "vulkan_problem", "rerun_executable", "verify_rrd", "free_port"]

INSTALL_HINT = "apt-get install -y mesa-vulkan-drivers"
"""What makes the viewer run on a machine without a GPU (Debian/Ubuntu: Mesa's llvmpipe Vulkan)."""

# Vulkan loader search path for installable client drivers (ICDs), Linux.
_ICD_DIRS = ("/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d", "/usr/local/share/vulkan/icd.d")


class ViewerUnavailable(RuntimeError):
    """The headless viewer cannot run on this machine; the message says why and what to install."""


def vulkan_problem() -> str | None:
    """Why the headless viewer cannot render here, or ``None`` if a Vulkan driver is present.

    Checks the Vulkan loader (``libvulkan.so.1``) and at least one installable client driver
    (ICD manifest in the loader's search path, or named by ``VK_ICD_FILENAMES`` /
    ``VK_DRIVER_FILES``). Linux only; elsewhere returns ``None`` and lets the viewer decide.
    """
    if not sys.platform.startswith("linux"):
        return None
    try:
        ctypes.CDLL("libvulkan.so.1")
    except OSError:
        return f"no Vulkan loader (libvulkan.so.1); install a software Vulkan driver: {INSTALL_HINT}"
    named = os.environ.get("VK_DRIVER_FILES") or os.environ.get("VK_ICD_FILENAMES")
    if named:
        manifests = [p for p in named.split(os.pathsep) if p]
        if not any(Path(p).exists() for p in manifests):
            return (
                f"VK_DRIVER_FILES/VK_ICD_FILENAMES name no existing driver manifest ({named}); "
                f"unset it or install a software Vulkan driver: {INSTALL_HINT}"
            )
        return None
    if not any(glob.glob(os.path.join(d, "*.json")) for d in _ICD_DIRS):
        return (
            "the Vulkan loader is installed but no Vulkan driver is (no ICD manifest in "
            f"{', '.join(_ICD_DIRS)}); install a software Vulkan driver: {INSTALL_HINT}"
        )
    return None


def rerun_executable() -> str:
    """The ``rerun`` command of the running interpreter's environment (matches the SDK version)."""
    beside = Path(sys.executable).parent / "rerun"
    if beside.is_file():
        return str(beside)
    found = shutil.which("rerun")
    if found is None:
        raise FileNotFoundError("no 'rerun' command beside the Python interpreter or on PATH (it comes with rerun-sdk)")
    return found


def verify_rrd(path: str | Path, timeout_s: float = 60.0) -> str:
    """Run ``rerun rrd verify`` on a file; returns its report, raises ``ValueError`` if it fails."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no recording at {path}")
    with path.open("rb") as fh:
        head = fh.read(4)
    if len(head) < 4 or not (head[:3] == b"RRF" and head[3:4].isdigit()):
        # `rerun rrd verify` passes a file too short to hold a message ("0 files verified without error")
        raise ValueError(f"rerun rrd verify {path} failed (exit 0): Not an RRD file: no RRF header, got {head!r}")
    proc = subprocess.run(
        [rerun_executable(), "rrd", "verify", str(path)], capture_output=True, text=True, timeout=timeout_s
    )
    report = (proc.stdout + proc.stderr).strip()
    if proc.returncode != 0 or "0 files verified" in report:
        raise ValueError(f"rerun rrd verify {path} failed (exit {proc.returncode}): {report}")
    return report


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])
