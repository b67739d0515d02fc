"""The ``factask`` command line (typer + rich).

Each command group lives in its own module and registers its commands on
:data:`app` when imported (below); heavy dependencies (MuJoCo, litellm) are
imported inside the commands so that ``factask --help`` and ``factask validate``
stay fast.
"""

from factask.cli import (  # noqa: F401 - importing a module registers its commands
    compat_cmds,
    data_cmds,
    gen_cmds,
    graph_cmds,
    library_cmds,
    policy_cmds,
    run_cmds,
)
from factask.cli.app import app

__all__ = ["app"]
