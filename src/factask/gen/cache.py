"""The disk cache of LLM answers: one JSON file per request, keyed on
everything that shapes the answer (model, messages, parameters, schema --
never the API key), written atomically so an interrupted run never leaves a
torn entry. A rerun is free and reproducible."""

from __future__ import annotations

import hashlib
import json
import os
import threading
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit, urlunsplit

#: Bumped when the cache entry layout changes, so old entries are not misread.
CACHE_VERSION = 3


def normalise_api_base(api_base: str | None) -> str | None:
    """``api_base`` as part of a cache key: scheme and host lower case, no
    user:password, no trailing slash (None stays None)."""
    if not api_base:
        return None
    parts = urlsplit(api_base.strip())
    host = (parts.hostname or "").lower()
    netloc = f"{host}:{parts.port}" if parts.port else host
    path = parts.path.rstrip("/")
    return urlunsplit((parts.scheme.lower(), netloc, path, parts.query, ""))


class ResponseCache:
    """Answers on disk, keyed on (model, messages, parameters): a rerun is free
    and reproducible.

    One JSON file per request (``<dir>/<key[:2]>/<key>.json``), written atomically
    (temporary file + rename) so an interrupted run never leaves a torn entry.

    Args:
        directory: Where entries live (created on first write).
    """

    def __init__(self, directory: str | os.PathLike[str]) -> None:
        self.directory = Path(directory)

    @staticmethod
    def key(model: str, messages: Sequence[Mapping[str, Any]], params: Mapping[str, Any],
            schema: Mapping[str, Any] | None) -> str:
        """SHA-256 of the canonical JSON of everything that shapes the answer."""
        blob = json.dumps({"v": CACHE_VERSION, "model": model, "messages": list(messages),
                           "params": dict(params), "schema": schema},
                          sort_keys=True, ensure_ascii=True, default=str)
        return hashlib.sha256(blob.encode()).hexdigest()

    def _path(self, key: str) -> Path:
        return self.directory / key[:2] / f"{key}.json"

    def get(self, key: str) -> dict[str, Any] | None:
        """The stored entry, or None (a corrupt entry counts as missing)."""
        path = self._path(key)
        try:
            data = json.loads(path.read_text())
        except (OSError, json.JSONDecodeError):
            return None
        if not isinstance(data, dict) or not isinstance(data.get("text"), str):
            return None
        return data

    def put(self, key: str, entry: Mapping[str, Any]) -> None:
        """Store ``entry`` under ``key`` (atomic replace)."""
        path = self._path(key)
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.{threading.get_ident()}.tmp")
        tmp.write_text(json.dumps(dict(entry), indent=1))
        os.replace(tmp, path)

    def __len__(self) -> int:
        return sum(1 for _ in self.directory.glob("*/*.json")) if self.directory.exists() else 0


__all__ = ["CACHE_VERSION", "ResponseCache", "normalise_api_base"]
