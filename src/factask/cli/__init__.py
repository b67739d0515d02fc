"""The ``factask`` command line (typer + rich).

Each command group lives in its own module and registers on :data:`app`; heavy
dependencies (MuJoCo, litellm) are imported inside the commands so that
``factask --help`` and ``factask validate`` stay fast.
"""

from factask.cli.app import app

__all__ = ["app"]
