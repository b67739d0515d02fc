"""Names (factask.vocabulary.names): one way to make a name unique, property-tested."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st


@given(st.lists(st.from_regex(r"[a-z][a-z0-9_]{0,70}", fullmatch=True), max_size=12),
       st.integers(8, 64))
def test_unique_name_never_repeats_and_stays_within_the_length(names, max_length) -> None:
    from factask.vocabulary.names import unique_name

    taken: set[str] = set()
    out = [unique_name(n[:max_length], taken, max_length) for n in names]
    assert len(set(out)) == len(out) and set(out) == taken
    assert all(len(o) <= max_length for o in out)
    for n, o in zip(names, out, strict=True):
        assert o == n[:max_length] or o.rsplit("_", 1)[1].isdigit()
