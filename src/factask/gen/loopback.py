"""A scripted, OpenAI-compatible chat server on the loopback interface.

Tests, examples and offline demos drive the *real* generation pipeline through
litellm against this server (model ``"openai/<anything>"``, ``api_base =
server.url``), so nothing is mocked between factask and the HTTP wire.

Replies come from a *responder*: any callable taking the decoded request body
and returning the assistant's text. :class:`ScriptedResponder` answers by the
generation step named in the conversation's first user message (every factask
prompt starts with ``Step: <step>``), which is what tests need: "the first
answer to the one-shot step is junk, the second is a valid graph".

Only the standard library is used (``http.server`` in a daemon thread).
"""

from __future__ import annotations

import json
import re
import threading
from collections.abc import Callable, Mapping, Sequence
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

from factask.vocabulary.errors import FactaskError

#: A responder maps the request body (``model``, ``messages``, ...) to reply text.
Responder = Callable[[dict[str, Any]], str]

_STEP_RE = re.compile(r"^Step:\s*(?P<step>[a-z_]+)(?:\s+\(subtask\s+`(?P<sub>[a-z0-9_]+)`\))?",
                      re.MULTILINE)


class CutReply(str):
    """A reply the responder cut at the request's ``max_tokens``: served with
    ``finish_reason: "length"``, as a provider reports an answer it stopped."""


class ScriptExhaustedError(FactaskError):
    """The scripted responder has no reply for a request."""


def conversation_step(messages: Sequence[Mapping[str, Any]]) -> tuple[str, str | None]:
    """The step (and subtask, if any) a conversation is about.

    Args:
        messages: Chat messages as sent to the server.

    Returns:
        ``(step, subtask)`` read from the first user message's ``Step:`` line;
        ``("", None)`` if there is none.
    """
    for m in messages:
        if m.get("role") != "user":
            continue
        content = m.get("content")
        if isinstance(content, list):  # content parts
            content = " ".join(str(p.get("text", "")) for p in content if isinstance(p, dict))
        match = _STEP_RE.search(str(content or ""))
        if match:
            return match.group("step"), match.group("sub")
        return "", None
    return "", None


class ScriptedResponder:
    """Replies by step: each key's replies are used in order, the last one repeats.

    Keys are ``"step"`` or ``"step:subtask"`` (the more specific key wins), e.g.
    ``{"one_shot": ["not json", GOOD_GRAPH]}``: the first one-shot request gets
    junk, every later one the graph. A callable value is called with the request.

    Attributes:
        calls: ``(key, reply index)`` of every request answered, in order.
    """

    def __init__(
        self,
        script: Mapping[str, str | Sequence[str] | Responder],
        default: Responder | None = None,
    ) -> None:
        self._script = {
            k: v if callable(v) or isinstance(v, str) else list(v) for k, v in script.items()
        }
        self._default = default
        self._used: dict[str, int] = {}
        self._lock = threading.Lock()
        self.calls: list[tuple[str, int]] = []

    def __call__(self, request: dict[str, Any]) -> str:
        step, sub = conversation_step(request.get("messages", []))
        keys = [f"{step}:{sub}", step] if sub else [step]
        for key in keys:
            if key in self._script:
                value = self._script[key]
                with self._lock:
                    i = self._used.get(key, 0)
                    self._used[key] = i + 1
                    self.calls.append((key, i))
                if callable(value):
                    return value(request)
                if isinstance(value, str):
                    return value
                return value[min(i, len(value) - 1)]
        if self._default is not None:
            with self._lock:
                self.calls.append(("<default>", 0))
            return self._default(request)
        raise ScriptExhaustedError(f"no scripted reply for step {keys[0]!r}")

    def count(self, key: str) -> int:
        """How many requests were answered from ``key``."""
        return sum(1 for k, _ in self.calls if k == key)


def _handler_class(server: LoopbackServer) -> type[BaseHTTPRequestHandler]:
    class Handler(BaseHTTPRequestHandler):
        protocol_version = "HTTP/1.1"

        def log_message(self, format: str, *args: Any) -> None:  # quiet
            return

        def _send(self, code: int, payload: dict[str, Any]) -> None:
            body = json.dumps(payload).encode()
            self.send_response(code)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

        def do_GET(self) -> None:
            if self.path.rstrip("/").endswith("/models"):
                self._send(200, {"object": "list", "data": [{"id": "scripted",
                                                             "object": "model"}]})
            else:
                self._send(404, {"error": {"message": "not found"}})

        def do_POST(self) -> None:
            length = int(self.headers.get("Content-Length") or 0)
            raw = self.rfile.read(length)
            if not self.path.rstrip("/").endswith("/chat/completions"):
                self._send(404, {"error": {"message": f"unknown path {self.path}"}})
                return
            try:
                request = json.loads(raw or b"{}")
            except json.JSONDecodeError:
                self._send(400, {"error": {"message": "request is not JSON"}})
                return
            server.requests.append(request)
            try:
                text = server.responder(request)
            except Exception as exc:  # a script error is a server error, not a crash
                self._send(500, {"error": {"message": f"{type(exc).__name__}: {exc}",
                                           "type": "server_error"}})
                return
            prompt_words = sum(len(str(m.get("content", "")).split())
                               for m in request.get("messages", []))
            completion_words = len(text.split())
            server.served += 1
            self._send(200, {
                "id": f"chatcmpl-loopback-{server.served}",
                "object": "chat.completion",
                "created": 0,
                "model": request.get("model", "scripted"),
                "choices": [{
                    "index": 0,
                    "message": {"role": "assistant", "content": str(text)},
                    "finish_reason": "length" if isinstance(text, CutReply) else "stop",
                }],
                # Word counts stand in for tokens: deterministic and good enough
                # to check that usage is recorded.
                "usage": {"prompt_tokens": prompt_words,
                          "completion_tokens": completion_words,
                          "total_tokens": prompt_words + completion_words},
            })

    return Handler


class LoopbackServer:
    """An OpenAI-compatible ``/v1/chat/completions`` endpoint on 127.0.0.1.

    Use as a context manager::

        with LoopbackServer(ScriptedResponder({...})) as server:
            client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url))

    Args:
        responder: Produces the reply text of each request.
        port: Port to bind; 0 picks a free one.

    Attributes:
        url: The API base (``http://127.0.0.1:PORT/v1``).
        requests: Every request body received, in order.
        served: Number of successful replies.
    """

    def __init__(self, responder: Responder, port: int = 0) -> None:
        self.responder = responder
        self.requests: list[dict[str, Any]] = []
        self.served = 0
        self._httpd = ThreadingHTTPServer(("127.0.0.1", port), _handler_class(self))
        self._httpd.daemon_threads = True
        self._thread: threading.Thread | None = None

    @property
    def port(self) -> int:
        return int(self._httpd.server_address[1])

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}/v1"

    def start(self) -> LoopbackServer:
        """Serve in a daemon thread; returns ``self``."""
        if self._thread is None:
            self._thread = threading.Thread(target=self._httpd.serve_forever,
                                            name="factask-loopback", daemon=True)
            self._thread.start()
        return self

    def stop(self) -> None:
        """Stop serving and close the socket."""
        if self._thread is not None:
            self._httpd.shutdown()
            self._thread.join()
            self._thread = None
        self._httpd.server_close()

    def __enter__(self) -> LoopbackServer:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.stop()
