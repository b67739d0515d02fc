"""Per-provider facts: how structured output is requested, how long the context is.

Providers disagree on structured output. OpenAI (and the providers litellm
translates it for) take ``response_format = {"type": "json_schema", "json_schema":
{...}}``; llama.cpp's OpenAI-compatible server rejects that form and takes
``{"type": "json_object", "schema": {...}}``; an unknown OpenAI-compatible
server may take neither, so the schema goes in the prompt only. The choice is
made here, once per client, by :func:`structured_form`; ``FACTASK_RESPONSE_FORMAT``
(or ``LLMConfig.response_format``) overrides it.

=================  ================================================  ==================
form               ``response_format`` sent                          for
=================  ================================================  ==================
``json_schema``    ``{"type": "json_schema", "json_schema": {...}}``  providers litellm
                                                                     says support it
``llama_cpp``      ``{"type": "json_object", "schema": {...}}``       the local model,
                                                                     llama.cpp servers
``json_object``    ``{"type": "json_object"}``                        JSON mode only
``prompt``         nothing (the schema is in the prompt)              anything else
=================  ================================================  ==================
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Mapping
from typing import Any, Literal

from factask.gen.llm_errors import provider_of

StructuredForm = Literal["json_schema", "llama_cpp", "json_object", "prompt"]
#: Every form, and ``auto`` (decide per provider) and ``off`` (= ``prompt``).
FORM_CHOICES: tuple[str, ...] = ("auto", "json_schema", "llama_cpp", "json_object", "prompt",
                                 "off")

#: Providers whose own API takes a JSON Schema (litellm translates the OpenAI form).
_SCHEMA_PROVIDERS = frozenset(["openai", "azure", "anthropic", "gemini", "vertex_ai",
                               "ollama", "ollama_chat", "mistral", "groq", "fireworks_ai",
                               "openrouter", "deepseek", "together_ai"])


def structured_form(model: str, api_base: str | None, local: bool,
                    requested: str = "auto") -> StructuredForm:
    """How to ask ``model`` for structured output.

    Args:
        model: litellm model string.
        api_base: The API base, if not the provider's default.
        local: The model is factask's local llama.cpp server.
        requested: ``auto`` or a form (``off`` means ``prompt``).

    Returns:
        The form: a requested one as is; with ``auto``, ``llama_cpp`` for the
        local server, ``prompt`` for an OpenAI-compatible server of unknown kind
        (``openai/...`` with an ``api_base``: vLLM, llama.cpp, LM Studio differ),
        ``json_schema`` for the providers in the table, else ``prompt``.
    """
    if requested == "off":
        return "prompt"
    if requested != "auto":
        return requested  # type: ignore[return-value]
    if local:
        return "llama_cpp"
    provider = provider_of(model)
    if provider == "openai" and api_base:
        return "prompt"
    return "json_schema" if provider in _SCHEMA_PROVIDERS else "prompt"


def response_format_param(form: StructuredForm, schema: Mapping[str, Any] | None,
                          name: str) -> dict[str, Any] | None:
    """The ``response_format`` argument of a request.

    Args:
        form: See :func:`structured_form`.
        schema: The step's JSON Schema (None: any JSON object).
        name: Schema name (letters, digits, ``_`` and ``-``).

    Returns:
        The parameter, or None to send none.
    """
    if form == "prompt":
        return None
    if schema is None or form == "json_object":
        return {"type": "json_object"}
    if form == "llama_cpp":
        return {"type": "json_object", "schema": for_llama_grammar(schema)}
    return {"type": "json_schema",
            "json_schema": {"name": name, "schema": dict(schema), "strict": False}}


#: llama-cpp-python's converter lets a JSON string hold any character but ``"`` and
#: ``\\`` -- raw newlines and other control characters too, which JSON forbids:
#: SmolLM2 wrote a newline inside a description and the answer did not parse.
_LOOSE_CHAR = 'char ::= [^"\\\\] |'
_JSON_CHAR = 'char ::= [^"\\\\\\x7F\\x00-\\x1F] |'


def llama_grammar(schema: Mapping[str, Any]) -> str | None:
    """The GBNF grammar of a step's schema for a llama.cpp server: llama-cpp-python's
    own converter (on :func:`for_llama_grammar`'s schema), with strings that cannot
    hold control characters. None where llama-cpp-python is not installed here (the
    server then converts the schema itself, from ``response_format``)."""
    try:
        from llama_cpp.llama_grammar import json_schema_to_gbnf
    except ImportError:
        return None
    import json

    gbnf = json_schema_to_gbnf(json.dumps(for_llama_grammar(schema)))
    return "\n".join(_JSON_CHAR + line[len(_LOOSE_CHAR):] if line.startswith(_LOOSE_CHAR)
                     else line for line in gbnf.splitlines())


def for_llama_grammar(schema: Any) -> Any:
    """The schema as llama.cpp's grammar converter should see it.

    A bounded repetition in a pattern makes the grammar slow (measured: a whole
    task graph decoded 2.5 times slower with the name pattern's ``{0,15}`` than
    with ``*``), so ``{0,n}`` becomes ``*`` and ``{1,n}`` becomes ``+`` -- except a
    group repeated at most four times, written out as that many optional copies,
    so that a name keeps its bounded number of parts; a string
    with both a ``pattern`` and a ``maxLength`` keeps only the length (the
    converter ignores ``maxLength`` beside a pattern, so a small model would write
    text until its token budget ran out). The converter ignores a number's
    bounds, so a number bounded on both sides becomes an enum of the round values
    within its bounds (:func:`grid_within`) (a size of 1.25 m or a weight of 3 can then
    not be written; a grid of round values is what a person would choose too).
    The answer is still checked against the whole schema, so nothing the grammar
    lets through goes unnoticed.
    """
    if isinstance(schema, list):
        return [for_llama_grammar(v) for v in schema]
    if not isinstance(schema, Mapping):
        return schema
    out = {k: for_llama_grammar(v) for k, v in schema.items()}
    if out.get("type") == "string" and "pattern" in out:
        if "maxLength" in out:
            del out["pattern"]
        else:
            out["pattern"] = _loosen(out["pattern"])
    if out.get("type") == "number" and "enum" not in out:
        values = grid_within(out)
        if values:
            out = {"enum": values}
    if out.get("type") == "integer" and "enum" not in out:
        counts = integers_within(out)
        if counts:
            out = {"enum": counts}
    return out


#: Integers a bounded integer may take under llama.cpp's grammar (a count).
ROUND_INTEGERS = (*range(0, 13), 16, 20, 24, 32, 48, 64, 100)


def integers_within(schema: Mapping[str, Any]) -> list[int]:
    """:data:`ROUND_INTEGERS` within an integer schema's bounds ([] if it is not
    bounded on both sides)."""
    lo, hi = schema.get("minimum"), schema.get("maximum")
    if not isinstance(lo, int) or not isinstance(hi, int) or isinstance(lo, bool) \
            or isinstance(hi, bool):
        return []
    return [v for v in ROUND_INTEGERS if lo <= v <= hi]


#: Mantissas of the round values a bounded number may take under llama.cpp's
#: grammar (times powers of ten).
ROUND_MANTISSAS = (1, 1.5, 2, 2.5, 3, 4, 5, 6, 8)
#: Decades of round values below a range's largest magnitude (two: 0.01 to 1 m
#: for a size). Few values keep grammar sampling fast: measured with SmolLM2 on
#: 2 busy cores, eight numbers took 2-3 s per token free or from 121 values, and
#: 0.2 s per token from 15.
ROUND_DECADES = 2
#: A range this wide is an angle in degrees: multiples of 45 instead.
ANGLE_RANGE = 90.0


def grid_within(schema: Mapping[str, Any]) -> list[float]:
    """The round values a number schema bounded on both sides may take under
    llama.cpp's grammar ([] if it is not bounded on both sides).

    Values: :data:`ROUND_MANTISSAS` times powers of ten, from the range's largest
    magnitude down :data:`ROUND_DECADES` decades, with both signs where the
    range has them and 0 where it holds it; multiples of 45 for an angle range
    (largest magnitude at least :data:`ANGLE_RANGE`). Only values within the
    bounds (exclusive ones excluded).
    """
    lo = schema.get("minimum", schema.get("exclusiveMinimum"))
    hi = schema.get("maximum", schema.get("exclusiveMaximum"))
    if isinstance(lo, bool) or isinstance(hi, bool) or not isinstance(lo, (int, float)) \
            or not isinstance(hi, (int, float)) or not lo < hi:
        return []
    top = max(abs(lo), abs(hi))
    if top >= ANGLE_RANGE:
        magnitudes = {45.0 * k for k in range(int(min(top, 360) // 45) + 1)}
    else:
        e_top = math.floor(math.log10(top))
        magnitudes = {round(m * 10.0 ** e, 9) for m in ROUND_MANTISSAS
                      for e in range(e_top - ROUND_DECADES, e_top + 1)}
        magnitudes = {v for v in magnitudes if top / 10 ** ROUND_DECADES <= v <= top} | {0.0}
    values = magnitudes | {-v for v in magnitudes}

    def inside(v: float) -> bool:
        low_ok = v > schema["exclusiveMinimum"] if "exclusiveMinimum" in schema else v >= lo
        high_ok = v < schema["exclusiveMaximum"] if "exclusiveMaximum" in schema else v <= hi
        return low_ok and high_ok

    return sorted(v for v in values if inside(v))


_UNBOUNDED_ZERO = re.compile(r"\{0,\d+\}")
_UNBOUNDED_ONE = re.compile(r"\{1,\d+\}")
#: A group repeated at most a few times (a name's ``(_[a-z0-9]{1,15}){0,3}``): written
#: out as that many optional copies, it stays bounded and cheap (only a character
#: class repeated many times makes the grammar slow).
_FEW_GROUPS = re.compile(r"(\([^()]*\))\{0,([1-4])\}")


def _loosen(pattern: str) -> str:
    """A pattern as the grammar should see it: a few repeats of a group written out,
    then a character class's bounded repetition unbounded (see
    :func:`for_llama_grammar`)."""
    pattern = _FEW_GROUPS.sub(lambda m: f"{m.group(1)}?" * int(m.group(2)), pattern)
    return _UNBOUNDED_ONE.sub("+", _UNBOUNDED_ZERO.sub("*", pattern))


def constrained(form: str) -> bool:
    """True if the form makes the provider enforce the schema (not just JSON)."""
    return form in ("json_schema", "llama_cpp")


def import_litellm() -> Any:
    """litellm, imported on first use with its bundled cost map (offline it would
    otherwise try to download it) and its debug banner off."""
    os.environ.setdefault("LITELLM_LOCAL_MODEL_COST_MAP", "True")
    import litellm

    litellm.suppress_debug_info = True
    return litellm


def context_window(model: str) -> int | None:
    """The model's input context in tokens as litellm knows it, or None.

    Args:
        model: litellm model string.

    Returns:
        ``max_input_tokens`` (else ``max_tokens``) of litellm's model info; None
        for a model litellm does not know.
    """
    litellm = import_litellm()
    try:
        info = litellm.get_model_info(model)
    except Exception:  # unknown to litellm: no limit known
        return None
    value = info.get("max_input_tokens") or info.get("max_tokens")
    return int(value) if value else None


__all__ = ["FORM_CHOICES", "StructuredForm", "constrained", "context_window", "for_llama_grammar",
           "import_litellm",
           "response_format_param", "structured_form"]
