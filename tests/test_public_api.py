"""The public API: everything in ``factask.__all__`` resolves; heavy parts load lazily."""

from __future__ import annotations

import subprocess
import sys

import factask


def test_every_public_name_resolves() -> None:
    for name in factask.__all__:
        assert getattr(factask, name) is not None, name


def test_import_does_not_pull_in_mujoco_or_litellm() -> None:
    code = ("import sys, factask; "
            "print(any(m in sys.modules for m in ('mujoco', 'litellm', 'dm_control')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "False"


def test_unknown_attribute_is_an_attribute_error() -> None:
    try:
        factask.no_such_thing  # noqa: B018
    except AttributeError as exc:
        assert "no_such_thing" in str(exc)
    else:
        raise AssertionError("expected AttributeError")
