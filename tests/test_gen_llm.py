"""The LLM client through litellm against the loopback server: config, cache, usage."""

from __future__ import annotations

import json
import socket

import pytest
from hypothesis import given
from hypothesis import strategies as st

from factask.gen.llm import LLMClient, LLMConfig, LLMConfigError, LLMError, ResponseCache
from factask.gen.loopback import LoopbackServer, ScriptedResponder, conversation_step

MSGS = [{"role": "system", "content": "be brief"},
        {"role": "user", "content": "Step: ping\nsay something"}]


def test_config_arguments_win_over_environment() -> None:
    env = {"FACTASK_MODEL": "openai/env-model", "FACTASK_API_BASE": "http://env/v1",
           "FACTASK_TEMPERATURE": "0.7", "FACTASK_RETRIES": "5"}
    cfg = LLMConfig.from_env(env, model="openai/arg-model", temperature=None)
    assert cfg.model == "openai/arg-model"
    assert cfg.api_base == "http://env/v1"
    assert cfg.temperature == pytest.approx(0.7)
    assert cfg.num_retries == 5


def test_config_without_model_is_the_local_model_and_bad_values_are_typed_errors() -> None:
    assert LLMConfig.from_env({}).model == "local/smollm2-135m"
    assert LLMConfig.from_env({}).is_local
    with pytest.raises(LLMConfigError, match="response_format"):
        LLMConfig.from_env({"FACTASK_RESPONSE_FORMAT": "xml"})
    with pytest.raises(LLMConfigError, match="FACTASK_TEMPERATURE"):
        LLMConfig.from_env({"FACTASK_MODEL": "x", "FACTASK_TEMPERATURE": "warm"})


def test_conversation_step_reads_the_first_user_message() -> None:
    msgs = [{"role": "system", "content": "Step: nope"},
            {"role": "user", "content": "Step: subtask_goal (subtask `put_red`)\n..."},
            {"role": "user", "content": "Step: other"}]
    assert conversation_step(msgs) == ("subtask_goal", "put_red")
    assert conversation_step([{"role": "user", "content": "hello"}]) == ("", None)


def test_call_records_usage_and_sends_the_schema(tmp_path) -> None:
    responder = ScriptedResponder({"ping": ['{"answer": "pong"}']})
    with LoopbackServer(responder) as server:
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     num_retries=0, response_format="json_schema"))
        reply = client.complete(MSGS, schema={"type": "object"}, schema_name="pong",
                                max_tokens=50)
    assert reply.text == '{"answer": "pong"}'
    assert not reply.cached
    assert reply.usage.prompt_tokens > 0 and reply.usage.completion_tokens == 2
    assert client.usage.calls == 1
    sent = server.requests[0]
    assert sent["response_format"]["type"] == "json_schema"
    assert sent["response_format"]["json_schema"]["schema"] == {"type": "object"}
    assert sent["messages"][1]["content"].startswith("Step: ping")
    assert sent["max_tokens"] == 50 and sent["seed"] == 0


def test_cache_makes_a_rerun_free_and_identical(tmp_path) -> None:
    responder = ScriptedResponder({"ping": ["first", "second"]})
    with LoopbackServer(responder) as server:
        cfg = LLMConfig(model="openai/scripted", api_base=server.url, num_retries=0)
        a = LLMClient(cfg, ResponseCache(tmp_path)).complete(MSGS)
        b = LLMClient(cfg, ResponseCache(tmp_path)).complete(MSGS)
        other_temp = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                         temperature=0.5, num_retries=0),
                               ResponseCache(tmp_path)).complete(MSGS)
    assert a.text == b.text == "first"
    assert b.cached and b.usage.cached_calls == 1 and b.usage.total_tokens == 0
    assert server.served == 2  # the cached call never reached the server
    assert other_temp.text == "second" and not other_temp.cached  # parameters are in the key
    assert len(ResponseCache(tmp_path)) == 2


def test_unreachable_endpoint_is_a_typed_error() -> None:
    with socket.socket() as s:  # a port that nothing listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    client = LLMClient(LLMConfig(model="openai/scripted", api_base=f"http://127.0.0.1:{port}/v1",
                                 num_retries=0, timeout=5))
    with pytest.raises(LLMError, match="failed"):
        client.complete(MSGS)


def test_script_error_is_a_server_error_not_a_hang() -> None:
    with LoopbackServer(ScriptedResponder({})) as server:
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     num_retries=0, timeout=5))
        with pytest.raises(LLMError):
            client.complete(MSGS)


# ---------------------------------------------------------------- review fixes
def _litellm_errors():
    import httpx
    import litellm

    e = litellm.exceptions
    req = httpx.Request("POST", "http://x/v1/chat/completions")

    def resp(code: int) -> httpx.Response:
        return httpx.Response(code, request=req)

    kw = {"llm_provider": "openai", "model": "m"}
    from factask.gen.llm import (
        LLMAuthError,
        LLMContextError,
        LLMModelNotFoundError,
        LLMQuotaError,
        LLMRequestError,
        LLMTransientError,
    )

    return [
        (e.APIConnectionError(message="refused", request=req, **kw), LLMTransientError),
        (e.Timeout(message="slow", **kw), LLMTransientError),
        (e.RateLimitError(message="429", response=resp(429), **kw), LLMTransientError),
        (e.ServiceUnavailableError(message="503", response=resp(503), **kw),
         LLMTransientError),
        (e.InternalServerError(message="500", response=resp(500), **kw), LLMTransientError),
        (e.ContextWindowExceededError(message="too long", response=resp(400), **kw),
         LLMContextError),
        (e.RateLimitError(message="You exceeded your current quota, check billing",
                          response=resp(429), **kw), LLMQuotaError),
        (e.NotFoundError(message="The model `gpt-9` does not exist", response=resp(404),
                         **kw), LLMModelNotFoundError),
        (e.InternalServerError(message="1 validation error: {'loc': ('body', "
                               "'response_format', 'type'), 'msg': \"Input should be 'text' "
                               "or 'json_object'\"}", response=resp(500), **kw),
         LLMRequestError),
        (e.BadRequestError(message="bad", response=resp(400), **kw), LLMRequestError),
        (e.ContentPolicyViolationError(message="policy", response=resp(400), **kw),
         LLMRequestError),
        (e.AuthenticationError(message="bad key", response=resp(401), **kw), LLMAuthError),
        (e.PermissionDeniedError(message="no", response=resp(403), **kw), LLMAuthError),
    ]


def test_provider_errors_are_classified(monkeypatch) -> None:
    from types import SimpleNamespace

    import factask.gen.llm as llm

    for exc, kind in _litellm_errors():
        assert llm.classify_llm_exception(exc) is kind, type(exc).__name__

        def completion(exc=exc, **kwargs):
            raise exc

        monkeypatch.setattr(llm, "_import_litellm",
                            lambda completion=completion: SimpleNamespace(completion=completion))
        client = LLMClient(LLMConfig(model="openai/x", num_retries=0))
        with pytest.raises(kind, match=type(exc).__name__):
            client.complete(MSGS)
    # Plain exceptions: by status code, else transient.
    err = type("Weird", (Exception,), {"status_code": 413})("x")
    assert llm.classify_llm_exception(err) is llm.LLMRequestError
    assert llm.classify_llm_exception(RuntimeError("?")) is llm.LLMTransientError


def test_cache_key_includes_the_normalised_api_base_but_no_key() -> None:
    a = LLMConfig(model="openai/x", api_base="http://Host:8000/v1/", api_key="sk-secret")
    b = LLMConfig(model="openai/x", api_base="http://host:8000/v1")
    c = LLMConfig(model="openai/x", api_base="http://other:8000/v1")
    assert a.cache_params() == b.cache_params() != c.cache_params()
    assert a.cache_params()["api_base"] == "http://host:8000/v1"
    assert "secret" not in json.dumps(a.cache_params())
    d = LLMConfig(model="openai/x", api_base="http://user:pw@host:8000/v1")
    assert "pw" not in json.dumps(d.cache_params())
    key = ResponseCache.key
    assert key("m", MSGS, a.cache_params(), None) != key("m", MSGS, c.cache_params(), None)


# ------------------------------------------------------- retries and fatal errors
class _Failing:
    """Loopback responder: raise (-> HTTP 500) for the first ``n`` requests."""

    def __init__(self, n: int) -> None:
        self.n, self.seen = n, 0

    def __call__(self, request):
        self.seen += 1
        if self.seen <= self.n:
            raise RuntimeError("overloaded")
        return '{"ok": true}'


def test_transient_errors_are_retried_with_bounded_backoff() -> None:
    responder = _Failing(2)
    with LoopbackServer(responder) as server:
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     num_retries=2, timeout=10))
        waits: list[float] = []
        client.sleep = waits.append
        assert client.complete(MSGS).text == '{"ok": true}'
    assert responder.seen == 3 and waits == [1.0, 2.0]
    responder = _Failing(5)
    with LoopbackServer(responder) as server:
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     num_retries=1, timeout=10))
        client.sleep = lambda s: None
        with pytest.raises(LLMError, match="failed"):
            client.complete(MSGS)
    assert responder.seen == 2  # one try + one retry, then the error


def test_fatal_errors_are_raised_at_once_with_the_fix(monkeypatch) -> None:
    from types import SimpleNamespace

    import httpx
    import litellm

    import factask.gen.llm as llm

    calls = []

    def completion(**kwargs):
        calls.append(kwargs)
        req = httpx.Request("POST", "http://x")
        raise litellm.exceptions.AuthenticationError(
            message="Incorrect API key provided", llm_provider="openai", model="gpt-4o",
            response=httpx.Response(401, request=req))

    monkeypatch.setattr(llm, "_import_litellm", lambda: SimpleNamespace(completion=completion))
    client = LLMClient(LLMConfig(model="openai/gpt-4o", num_retries=3))
    client.sleep = lambda s: pytest.fail("a fatal error must not be retried")
    with pytest.raises(llm.LLMAuthError) as info:
        client.complete(MSGS)
    assert len(calls) == 1 and calls[0]["num_retries"] == 0 and calls[0]["max_retries"] == 0
    line = info.value.line()
    assert "\n" not in line and "Incorrect API key" in line and "OPENAI_API_KEY" in line


def test_a_timed_out_request_is_abandoned_on_the_server_side() -> None:
    import time as _time

    def slow(request):
        _time.sleep(3)
        return "late"

    abandoned: list[int] = []
    with LoopbackServer(slow) as server:
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     num_retries=1, timeout=1),
                           on_abandon=lambda: abandoned.append(1))
        client.sleep = lambda s: None
        with pytest.raises(LLMError, match="Timeout"):
            client.complete(MSGS)
    assert abandoned == [1, 1]  # each timed-out try restarts the server (local model)


def test_a_chunked_model_package_is_joined_once_into_the_model_cache(tmp_path, monkeypatch):
    from factask.gen import local

    pkg = tmp_path / "site" / "fake_chunked_gguf"
    pkg.mkdir(parents=True)
    # The package's documented API: assemble(output_path, overwrite) joins its parts.
    (pkg / "__init__.py").write_text(
        "from pathlib import Path\n"
        "CALLS = []\n"
        "def assemble(output_path, overwrite=False):\n"
        "    CALLS.append(str(output_path))\n"
        "    Path(output_path).write_bytes(b'GGUF' + b'0' * 8)\n"
        "    return Path(output_path)\n")
    monkeypatch.syspath_prepend(str(tmp_path / "site"))
    monkeypatch.setenv("FACTASK_MODEL_CACHE", str(tmp_path / "models"))
    spec = local.LocalModelSpec("fake", "fake_chunked_gguf", "fake.gguf", 2048,
                                "pip install fake", chunked=True)
    monkeypatch.setitem(local.LOCAL_MODELS, "fake", spec)
    found, path = local.resolve_local("local/fake")
    assert found is spec and path == tmp_path / "models" / "fake.gguf"
    assert path.read_bytes().startswith(b"GGUF")

    missing = local.LocalModelSpec("gone", "no_such_package_xyz", "g.gguf", 2048,
                                   "pip install gone", chunked=True)
    monkeypatch.setitem(local.LOCAL_MODELS, "gone", missing)
    with pytest.raises(local.LocalModelError, match="pip install gone"):
        local.resolve_local("local/gone")


def test_the_local_server_takes_the_free_cores_and_keeps_a_prompt_cache() -> None:
    from factask.gen.local import LOCAL_MODELS, LocalLlamaServer, default_threads

    assert default_threads({}, load=0.1, cores=2) == 2
    assert default_threads({}, load=1.2, cores=2) == 1
    assert default_threads({}, load=9.0, cores=2) == 1  # busier than its cores: one thread
    assert default_threads({"FACTASK_LOCAL_THREADS": "3"}, load=9.0, cores=2) == 3
    assert default_threads({"FACTASK_LOCAL_THREADS": "x"}, load=0.0, cores=4) == 4
    server = object.__new__(LocalLlamaServer)  # the command line only, no process
    server.spec, server.path = LOCAL_MODELS["smollm2-135m"], "m.gguf"
    server.n_ctx, server.n_threads, server.alias, server.python = 8192, 1, "a", "py"
    cmd = server.command(1234)
    assert cmd[cmd.index("--cache") + 1] == "true" and "--cache_size" in cmd
    assert cmd[cmd.index("--n_threads") + 1] == "1"


def test_the_llama_cpp_form_sends_a_grammar_whose_strings_hold_no_control_characters() -> None:
    pytest.importorskip("llama_cpp")
    from factask.gen.providers import llama_grammar

    schema = {"type": "object", "properties": {"text": {"type": "string", "maxLength": 30}},
              "required": ["text"], "additionalProperties": False}
    grammar = llama_grammar(schema)
    assert grammar is not None
    char = next(line for line in grammar.splitlines() if line.startswith("char ::="))
    assert char.startswith('char ::= [^"\\\\\\x7F\\x00-\\x1F] |'), char
    with LoopbackServer(lambda request: '{"text": "ok"}') as server:
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     response_format="llama_cpp", num_retries=0, timeout=10))
        client.complete(MSGS, schema=schema)
    sent = server.requests[-1]
    assert sent["grammar"] == grammar and "response_format" not in sent


def test_a_model_without_a_system_turn_gets_its_system_prompt_in_the_first_user_turn() -> None:
    """Gemma's chat format drops system messages: the client folds them in."""
    from factask.gen.local import LOCAL_MODELS, LocalLlamaServer

    responder = ScriptedResponder({"ping": ['{"answer": "pong"}']})
    with LoopbackServer(responder) as server:
        client = LLMClient(LLMConfig(model="openai/scripted", api_base=server.url,
                                     num_retries=0), system_role=False)
        client.complete(MSGS, max_tokens=20)
    sent = server.requests[0]["messages"]
    assert [m["role"] for m in sent] == ["user"]
    assert sent[0]["content"] == f"{MSGS[0]['content']}\n\n{MSGS[1]['content']}"
    gemma = LOCAL_MODELS["gemma3-270m"]
    assert not gemma.system_role
    srv = object.__new__(LocalLlamaServer)  # the command line only, no process
    srv.spec, srv.path = gemma, "m.gguf"
    srv.n_ctx, srv.n_threads, srv.alias, srv.python = 4096, 1, "a", "py"
    cmd = srv.command(1234)
    assert cmd[cmd.index("--chat_format") + 1] == "gemma"
    srv.spec = LOCAL_MODELS["smollm2-135m"]  # its GGUF carries its own template
    assert "--chat_format" not in srv.command(1234)


_roles = st.sampled_from(["system", "user", "assistant"])
_messages = st.lists(st.fixed_dictionaries({"role": _roles, "content": st.text(max_size=8)}),
                     max_size=6)


@given(_messages)
def test_folding_system_messages_keeps_every_other_message_and_all_system_text(msgs) -> None:
    from factask.gen.llm import fold_system_messages

    folded = fold_system_messages(msgs)
    assert all(m["role"] != "system" for m in folded)
    others = [m for m in msgs if m["role"] != "system"]
    system = [m["content"] for m in msgs if m["role"] == "system"]
    if not system:
        assert folded == others
        return
    head = "\n\n".join(system)
    first_user = next((i for i, m in enumerate(others) if m["role"] == "user"), None)
    if first_user is None:
        assert folded == [{"role": "user", "content": head}, *others]
    else:
        assert folded[first_user]["content"] == f"{head}\n\n{others[first_user]['content']}"
        assert [m for i, m in enumerate(folded) if i != first_user] == \
            [m for i, m in enumerate(others) if i != first_user]
