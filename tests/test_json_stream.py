"""The one JSON stream splitter (impactlab.io.json_stream): the decoder finds each value's end; a stream read in
pieces waits for a value cut short and refuses one no continuation can mend."""

from __future__ import annotations

import json

import pytest

from impactlab.io.json_stream import JsonObjectStream, NotJsonError, json_values

#: objects whose every cut tests a case of "cut short": numbers (1.5e-3, -0), literals, \u escapes, a two-byte and
#: a four-byte UTF-8 character, braces and escaped quotes inside strings
OBJECTS = [b'{"Speed": 1.5e-3, "HLA": -0, "ok": true, "no": false, "x": null, "s": "\\ud83c\\udfcc"}',
           b'{"Message": "caf\\u00e9 \xc3\xa9 \xf0\x9f\x8f\x8c } { \\" ", "Code": 201}',
           b'{"Player": {"Handed": "RH", "Club": "DR"}, "Code": 201, "n": [1, 2.25, -3e2]}']


def test_every_cut_of_a_stream_gives_the_same_objects():
    stream = b" " + b"\r\n".join(OBJECTS) + b"\n"
    for cut in range(1, len(stream)):  # two reads, cut at every byte
        splitter = JsonObjectStream(limit=1024)
        found = splitter.feed(stream[:cut]) + splitter.feed(stream[cut:])
        assert found == OBJECTS, cut
        assert not splitter.pending
    splitter = JsonObjectStream(limit=1024)
    assert [item for byte in stream for item in splitter.feed(bytes([byte]))] == OBJECTS
    assert [json.loads(item) for item in OBJECTS][1]["Message"].startswith("café é")


@pytest.mark.parametrize("bad", [b'{"Code": two hundred}', b'{"Code": 1.x}', b'{"a": "x\ny"}', b'{"a" 1}',
                                 b'{"a": 1 2}', b'{"a": "\\uzzzz"}', b'{"a": tru }'])
def test_an_object_no_continuation_can_mend_is_refused_at_once(bad):
    with pytest.raises(NotJsonError, match="a reply that is not JSON"):
        JsonObjectStream(limit=1024).feed(bad)


def test_a_cut_object_waits_and_text_outside_objects_is_refused_unless_skipped():
    splitter = JsonObjectStream(limit=1024, skip=b"hello")
    assert splitter.feed(b'hel') == [] and splitter.pending
    assert splitter.feed(b'lo{"a": [1, tr') == [] and splitter.pending
    assert splitter.feed(b'ue]}') == [b'{"a": [1, true]}'] and not splitter.pending
    with pytest.raises(NotJsonError, match="text that is not a JSON object"):
        JsonObjectStream(limit=1024).feed(b'[1, 2]')
    with pytest.raises(NotJsonError, match="longer than 16 bytes"):
        JsonObjectStream(limit=16).feed(b'{"a": "' + b"x" * 20)


def test_a_text_of_values_is_split_where_each_ends():
    text = '\ufeff{"a": 1}{"b": [2, 3]}\n\n  [4]  '
    assert list(json_values(text)) == [(1, {"a": 1}, 9), (9, {"b": [2, 3]}, 22), (26, [4], 29)]
    with pytest.raises(json.JSONDecodeError) as bad:
        list(json_values('{"a": 1}\n{"b": }'))
    assert (bad.value.lineno, bad.value.colno) == (2, 7)


def test_an_object_nested_past_the_bound_is_read_to_its_end_and_refused_and_the_stream_stays_in_step():
    """A reply 30,000 deep arrives in reads of 4 KiB: refused whole once its end has come (no RecursionError, no
    early refusal that would cut the sender off), and the reply after it is still read."""
    from impactlab.foreign import MAX_NESTING, json_value_end

    deep = b'{"Code":200,"Player":' + b"[" * 30_000 + b'"]["' + b"]" * 30_000 + b"}"
    assert json_value_end(deep.decode()) == len(deep)  # brackets inside the string do not count
    assert json_value_end(deep[:-1].decode()) == -1
    stream = JsonObjectStream(limit=1 << 20)
    refused = None
    chunks = [deep[i:i + 4096] for i in range(0, len(deep), 4096)] + [b'{"Code":200}']
    for index, chunk in enumerate(chunks):
        try:
            items = stream.feed(chunk)
        except NotJsonError as exc:
            refused = index
            assert f"nests more than {MAX_NESTING} levels deep" in str(exc)
            items = stream.feed(b"")
        if index < len(chunks) - 2:
            assert refused is None and items == []
    assert refused == len(chunks) - 2
    assert items == [b'{"Code":200}']


def test_a_good_object_before_a_deep_one_is_taken_and_the_deep_one_refused():
    """Both in one read: the good reply comes out, the refusal names the deep one (review: the good one was refused)."""
    stream = JsonObjectStream(limit=1 << 20)
    deep = b'{"Code":201,"Player":' + b"[" * 150 + b"]" * 150 + b"}"
    with pytest.raises(NotJsonError) as refused:
        stream.feed(b'{"Code":200,"Message":"ok"}' + deep)
    assert "nests more than" in str(refused.value) and '"Code":200' not in str(refused.value)
