"""Write the MJCF of every asset kind (default size) and of the table to mjcf_assets/.

The files are generated, never edited by hand; ``tests/test_assets.py`` fails when
they differ from what the builders in :mod:`factask.sim.build.mjcf` produce now.

Usage:
    .venv/bin/python scripts/export_assets.py [OUT_DIR]
"""

from __future__ import annotations

import sys
from pathlib import Path

import factask.sim  # noqa: F401  (picks the headless GL backend before MuJoCo loads)
from factask.sim.build.mjcf import asset_xml, table_xml
from factask.vocabulary.kinds import KIND_NAMES

#: Where the files go, relative to the repository root.
DEFAULT_OUT = Path(__file__).resolve().parent.parent / "mjcf_assets"


def expected_files() -> dict[str, str]:
    """File name -> XML text of every exported asset (and the table).

    Returns:
        ``{"block.xml": ..., ..., "table.xml": ...}`` in a fixed order.
    """
    files = {f"{kind}.xml": asset_xml(kind) for kind in KIND_NAMES}
    files["table.xml"] = table_xml()
    return files


def main(out: Path = DEFAULT_OUT) -> list[Path]:
    """Write every file of :func:`expected_files` into ``out``.

    Args:
        out: Output folder (created if missing).

    Returns:
        The paths written.
    """
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, text in expected_files().items():
        path = out / name
        path.write_text(text, encoding="utf-8")
        written.append(path)
    return written


if __name__ == "__main__":
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT_OUT
    for p in main(target):
        print(p)
