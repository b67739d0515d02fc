"""Stand-in for ``cliport.tasks.cameras``: camera configs a task may name.

factask renders with its own cameras; these only let ``Task.__init__``-style
code that reads ``cameras.Oracle.CONFIG`` run.
"""

from __future__ import annotations

from typing import Any, ClassVar


class Oracle:
    """Top-down oracle camera (placeholder config)."""

    CONFIG: ClassVar[list[dict[str, Any]]] = [{"image_size": (480, 640), "name": "oracle"}]


class RealSenseD415:
    """Three RealSense cameras (placeholder config)."""

    CONFIG: ClassVar[list[dict[str, Any]]] = [{"image_size": (480, 640), "name": f"rs{i}"}
                                    for i in range(3)]
