"""The real local model: llama-cpp-python's server with the packaged SmolLM2-135M.

Every test here talks to the real server (started once per module, on one xdist
worker): each structured-output form as the server answers it, the token
budget, and a short end-to-end ``factask generate`` (one task, bounded tokens,
temperature 0, fixed seed).
"""

from __future__ import annotations

import json
import urllib.error
import urllib.request

import pytest
from jsonschema import Draft202012Validator
from typer.testing import CliRunner

from factask.gen.conversation import Budget
from factask.gen.llm import LLMClient, LLMConfig, LLMContextError, LLMRequestError
from factask.gen.local import LocalLlamaServer
from factask.gen.providers import structured_form
from factask.gen.session import LOCAL_SECONDS_PER_TOKEN, open_client

pytestmark = pytest.mark.xdist_group("llama-server")

ALIAS = "smollm2-135m"
MSGS = [{"role": "system", "content": "You answer with JSON only."},
        {"role": "user", "content": "Which colour is the sky? Give the colour and a count."}]
SCHEMA = {"type": "object", "properties": {"color": {"type": "string",
                                                     "enum": ["blue", "red", "green"]},
                                           "count": {"type": "integer"}},
          "required": ["color", "count"], "additionalProperties": False}


@pytest.fixture(scope="module")
def server():
    with LocalLlamaServer() as srv:
        yield srv


def _client(server: LocalLlamaServer, form: str) -> LLMClient:
    config = LLMConfig(model=f"local/{ALIAS}", api_base=server.url, response_format=form,
                       num_retries=0, timeout=120)
    return LLMClient(config, wire_model=f"openai/{ALIAS}", context=server.n_ctx,
                     counter=server.count_messages,
                     seconds_per_token=LOCAL_SECONDS_PER_TOKEN)


def test_auto_picks_llama_cpps_form_for_the_local_server(server) -> None:
    assert structured_form(f"openai/{ALIAS}", server.url, local=True) == "llama_cpp"
    assert _client(server, "auto").form == "llama_cpp"


def test_llama_cpp_form_constrains_the_answer_to_the_schema(server) -> None:
    reply = _client(server, "llama_cpp").complete(MSGS, schema=SCHEMA, max_tokens=40)
    data = json.loads(reply.text)  # a grammar: always JSON of this shape
    assert not list(Draft202012Validator(SCHEMA).iter_errors(data))
    assert reply.usage.completion_tokens <= 40 and reply.usage.prompt_tokens > 0


def test_openai_json_schema_form_is_rejected_by_the_server_and_not_retried(server) -> None:
    # The reason the table sends llama.cpp its own form: the OpenAI form is a 4xx/5xx
    # validation error there, a request error (the model's failure), not an outage.
    with pytest.raises(LLMRequestError, match="json_object"):
        _client(server, "json_schema").complete(MSGS, schema=SCHEMA, max_tokens=40)


def test_json_object_form_gives_a_json_object(server) -> None:
    reply = _client(server, "json_object").complete(MSGS, schema=None, max_tokens=40)
    text = reply.text.strip()
    assert text.startswith("{")  # any object; cut at max_tokens it may not close


def test_prompt_form_sends_no_format_and_answers_free_text(server) -> None:
    client = _client(server, "prompt")
    assert client.form == "prompt"
    reply = client.complete(MSGS, schema=SCHEMA, max_tokens=20)
    assert isinstance(reply.text, str) and reply.usage.completion_tokens <= 20


def test_tokens_are_counted_by_the_server_and_a_prompt_too_long_fails_before_a_call(
        server) -> None:
    short = server.count_messages(MSGS)
    longer = server.count_messages([*MSGS, {"role": "user", "content": "word " * 200}])
    assert 0 < short < longer and longer - short >= 200
    client = _client(server, "llama_cpp")
    budget = Budget(client, client.config.model)
    huge = [{"role": "user", "content": "block " * (server.n_ctx + 100)}]
    with pytest.raises(LLMContextError, match="context of 8192 tokens"):
        budget.choose("one_shot", lambda level: huge, 500)
    assert client.usage.calls == 0  # nothing was sent


def test_the_client_context_manager_starts_and_stops_the_server(tmp_path) -> None:
    with open_client(LLMConfig(num_retries=0)) as client:
        url = client.config.api_base
        assert client.context == 8192 and client.form == "llama_cpp"
        with urllib.request.urlopen(f"{url}/models", timeout=5) as r:
            assert ALIAS in r.read().decode()
    with pytest.raises((urllib.error.URLError, OSError)):
        urllib.request.urlopen(f"{url}/models", timeout=2)


def test_generate_end_to_end_with_the_local_model(tmp_path) -> None:
    from factask.cli import app

    # 80 tokens: the answer is cut (exit 1) but the call completes, within its
    # timeout, even on a busy machine (grammar sampling: up to ~3 s per token).
    env = {"FACTASK_MAX_TOKENS": "80", "FACTASK_CACHE": "", "FACTASK_MODEL": ""}
    out = tmp_path / "g.json"
    res = CliRunner().invoke(app, ["generate", "place-red-in-green: put the red block in the "
                                   "green zone", "-a", "one-shot", "--max-repairs", "0",
                                   "--episodes", "1", "--temperature", "0", "--seed", "0",
                                   "--out", str(out)], env=env)
    # Completion is not expected of a 135M model; what must hold: the local server
    # answered (exit 0 or 1, never 2 = configuration or 3 = no call succeeded).
    assert res.exit_code in (0, 1), res.output
    assert "local/smollm2-135m, structured output: llama_cpp" in res.output
    assert "1 call(s) (0 cached)" in res.output
    assert "Traceback" not in res.output
    assert res.exit_code == 1 or out.exists()


def test_a_server_that_died_is_started_again_before_the_next_request() -> None:
    import os
    import signal

    with LocalLlamaServer() as srv:
        assert not srv.revive()  # running: nothing to do
        before = srv.count_messages(MSGS)
        assert srv._proc is not None
        os.kill(srv._proc.pid, signal.SIGKILL)  # as a grammar its parser rejects did
        srv._proc.wait(timeout=10)
        client = _client(srv, "llama_cpp")
        client.before_call = srv.revive
        assert srv.count_messages(MSGS) == before  # revived by the count
        assert srv.restarts == 1 and len(srv.deaths) == 1
        os.kill(srv._proc.pid, signal.SIGKILL)
        srv._proc.wait(timeout=10)
        reply = client.complete(MSGS, schema=SCHEMA, max_tokens=20)  # revived by the call
        assert json.loads(reply.text)["color"] in ("blue", "red", "green")
        assert srv.restarts == 2
    assert not srv.revive()  # stopped on purpose: not started again


def test_a_server_that_keeps_dying_at_once_stops_the_run_with_the_fix() -> None:
    import os
    import signal

    from factask.gen.llm_errors import LLMFatalError
    from factask.gen.local import TESTED_LLAMA_CPP, LocalServerCrashError

    with LocalLlamaServer() as srv:
        for attempt in range(srv.QUICK_DEATHS_FATAL):
            assert srv._proc is not None
            os.kill(srv._proc.pid, signal.SIGKILL)  # as a build that crashes on this CPU
            srv._proc.wait(timeout=10)
            if attempt < srv.QUICK_DEATHS_FATAL - 1:
                assert srv.revive()  # one death, or two, may be a bad request: restart
        with pytest.raises(LocalServerCrashError) as info:
            srv.revive()
    assert isinstance(info.value, LLMFatalError)  # the run stops, no retries
    line = info.value.line()
    assert "killed by SIGKILL" in line and f"=={TESTED_LLAMA_CPP}" in line
    assert "\n" not in line
    assert not srv.running
