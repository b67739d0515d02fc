"""Where a batch runs: the optional GPU packages and the Warp device.

The batched backend runs on MuJoCo Warp (``mujoco-warp``, ``warp-lang``), which the
``gpu`` extra installs (``pip install 'factask[gpu]'``). The same code runs on a
CUDA GPU or on Warp's CPU device (slow, for tests and CI). Nothing here imports
Warp at module import: ``import factask.batch`` works without the extra, and
asking for a batch without it raises :class:`BatchBackendMissing`.
"""

from __future__ import annotations

import importlib
import sys
from types import ModuleType

from factask.vocabulary.errors import FactaskError, InvalidValueError

#: The extra that installs the backend.
GPU_EXTRA = "gpu"
#: The pip line that installs it.
INSTALL_HINT = "pip install 'factask[gpu]'  (mujoco-warp and warp-lang)"
_QUIETED = False


class BatchBackendMissing(FactaskError, ImportError):
    """MuJoCo Warp / Warp are not installed (the ``gpu`` extra); an ``ImportError`` too."""


class DeviceUnavailableError(FactaskError, RuntimeError):
    """A device was asked for that this machine does not have (no CUDA GPU, or not that
    many); a ``RuntimeError`` too."""


def load_backend() -> tuple[ModuleType, ModuleType]:
    """Import Warp and MuJoCo Warp, initialising Warp quietly.

    Returns:
        (``warp``, ``mujoco_warp``).

    Raises:
        BatchBackendMissing: either package is missing (or fails to import).
    """
    global _QUIETED
    try:
        wp = importlib.import_module("warp")
        if not _QUIETED:  # before anything initialises Warp: no banner, no line per
            _QUIETED = True  # compiled module (warnings stay)
            if hasattr(wp, "LOG_WARNING"):
                wp.config.log_level = wp.LOG_WARNING
            else:  # Warp before log levels
                wp.config.quiet = True
        mjw = importlib.import_module("mujoco_warp")
    except ImportError as exc:
        raise BatchBackendMissing(
            f"the batched backend needs MuJoCo Warp and Warp ({exc}); install the "
            f"'{GPU_EXTRA}' extra: {INSTALL_HINT}") from exc
    wp.init()  # idempotent
    return wp, mjw


def resolve_device(device: str | None = None) -> str:
    """The Warp device name for ``device``, checked against this machine.

    Args:
        device: ``"cpu"``, ``"cuda"`` (the first GPU), ``"cuda:N"``, or None (the
            first GPU if there is one, else the CPU).

    Returns:
        A Warp device name (``"cpu"`` or ``"cuda:N"``).

    Raises:
        BatchBackendMissing: the ``gpu`` extra is not installed.
        DeviceUnavailableError: a CUDA device was asked for and this machine has none
            (or fewer).
        InvalidValueError: not a device name.
    """
    wp, _ = load_backend()
    count = int(wp.get_cuda_device_count())
    if device is None:
        return "cuda:0" if count else "cpu"
    name = str(device).strip().lower()
    if name == "cpu":
        return "cpu"
    if name == "cuda" or name.startswith("cuda:"):
        index_text = name.partition(":")[2] or "0"
        if not index_text.isdigit():
            raise InvalidValueError(f"device {device!r}: expected 'cuda:N' with N a number")
        index = int(index_text)
        if count == 0:
            raise DeviceUnavailableError(
                f"device {device!r} asked for, but Warp finds no CUDA GPU on this machine "
                "(no NVIDIA driver or no GPU); use device='cpu' (slow: tests and CI) or run "
                "on a machine with a GPU")
        if index >= count:
            raise DeviceUnavailableError(f"device {device!r} asked for, but this machine has "
                                         f"{count} CUDA GPU(s) (cuda:0 .. cuda:{count - 1})")
        return f"cuda:{index}"
    raise InvalidValueError(f"device {device!r}: expected 'cpu', 'cuda', 'cuda:N' or None")


__all__ = ["GPU_EXTRA", "INSTALL_HINT", "BatchBackendMissing", "DeviceUnavailableError",
           "load_backend", "resolve_device"]


#: Said once per process: the first batch on the CPU waits for Warp's compiler.
_COMPILE_NOTICE_GIVEN = False


def announce_cpu_compile(device: str) -> None:
    """Say once, on stderr, that the first batched step on the CPU compiles Warp's
    kernels (90 s to 5 minutes on 2 cores; cached on disk afterwards), so a first run
    that seems to hang is explained. Nothing on a GPU (seconds there) or the second time.

    Args:
        device: The resolved Warp device name.
    """
    global _COMPILE_NOTICE_GIVEN
    if device != "cpu" or _COMPILE_NOTICE_GIVEN:
        return
    _COMPILE_NOTICE_GIVEN = True
    try:
        import warp as wp

        cache = wp.config.kernel_cache_dir or "Warp's kernel cache"
    except Exception:  # the notice must never fail the batch
        cache = "Warp's kernel cache"
    print(f"factask: the batched backend on the CPU compiles Warp's kernels the first time "
          f"(90 s to 5 minutes; cached in {cache} afterwards)", file=sys.stderr, flush=True)

