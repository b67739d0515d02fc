"""factask: robot manipulation tasks as explicit factor graphs, compiled to MuJoCo.

The public API of the graph model is re-exported here; the MuJoCo backend lives
in :mod:`factask.sim`, generation in :mod:`factask.gen` (imported lazily: they
pull in heavy dependencies).
"""

from factask.model import *  # noqa: F403
from factask.model import __all__ as _model_all

__version__ = "0.1.0"
__all__ = [*_model_all, "__version__"]
