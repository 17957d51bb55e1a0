"""The depth scan that guards libyaml's composer is skipped only where a count of characters proves it would pass."""

from pathlib import Path

import pytest

from impactlab.errors import StudyError
from impactlab.study.yaml_lines import MAX_YAML_DEPTH, load_yaml, nesting_bound, nesting_depth

DEEP = ["[" * 500 + "]" * 500, "- " * 500 + "x", "{a: " * 500 + "1" + "}" * 500,
        "".join(" " * i + "a:\n" for i in range(150)) + " " * 150 + "b: 1\n",
        "".join(" " * i + "a:\u2028" for i in range(150)) + " " * 150 + "b: 1\n",  # lines split by U+2028
        "".join(" " * i + "a:\r\n" for i in range(150)) + " " * 150 + "b: 1\r\n"]
SHALLOW = ["a:\n  b:\n    c: [1, [2, {x: 3}]]\n", "- - - x\n", 'title: "[[[[[[[[[[[[[["\nname: x[[[[[[\n',
           "a:\x85  b:\x0c    c: 1\x1c", "? - a\n: - b\n", "-\n -\n  -\n"]
STUDIES = [path.read_text() for path in Path(__file__).resolve().parents[1].glob("studies/**/*.yaml")]


@pytest.mark.parametrize("text", DEEP + SHALLOW + STUDIES)
def test_the_bound_is_never_below_the_scanned_depth(text):
    assert nesting_depth(text)[0] <= nesting_bound(text)


def test_a_text_nested_too_deep_is_refused_and_a_long_shallow_one_read():
    for text in DEEP:
        assert nesting_bound(text) > MAX_YAML_DEPTH
        with pytest.raises(StudyError, match="nests more than 100 levels deep"):
            load_yaml(text, "deep.yaml")
    long = "".join(f"k{i}: [{i}, -{i}]\n" for i in range(200))  # bound ~800: scanned, depth 2, read
    assert nesting_bound(long) > MAX_YAML_DEPTH and load_yaml(long)[0]["k199"] == [199, -199]
    assert all(nesting_bound(text) <= MAX_YAML_DEPTH for text in STUDIES)  # the shipped studies skip the scan
