"""Bad scene files and dicts: every way the text or the data can be wrong is a one-line
ValueError naming the file and the entry (issue 20, item 3), never a RecursionError, an
OverflowError or a key silently dropped."""

from __future__ import annotations

import json

import planarkin as pk
import pytest
from planarkin.scene._parse import MAX_DEPTH


def one_line(e: pytest.ExceptionInfo) -> str:
    msg = str(e.value)
    assert "\n" not in msg
    return msg


def write(tmp_path, name: str, text: str):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


@pytest.mark.parametrize(
    "name, text",
    [
        ("deep.json", "[" * 100_000 + "]" * 100_000),  # beyond the JSON reader's recursion
        ("deep.toml", "a = " + "[" * 100_000 + "]" * 100_000),
    ],
)
def test_nesting_beyond_the_reader_is_a_value_error_naming_the_file(tmp_path, name, text):
    p = write(tmp_path, name, text)
    with pytest.raises(ValueError) as e:
        pk.Scene.load(p)
    assert one_line(e).startswith(f"{p}: nested too deeply")


def test_nesting_deeper_than_a_scene_names_the_entry(tmp_path):
    d = pk.scenes.data("fourbar")
    deep: object = 1.0
    for _ in range(MAX_DEPTH + 3):
        deep = [deep]
    d["description"] = deep
    with pytest.raises(ValueError) as e:
        pk.Scene.from_dict(d)
    assert one_line(e).startswith("scene: description[0]")
    p = write(tmp_path, "deep.json", json.dumps(d))
    with pytest.raises(ValueError) as e:
        pk.Scene.load(p)
    assert one_line(e).startswith(f"{p}: description[0]")


def test_a_400_digit_coordinate_names_the_point(tmp_path):
    d = pk.scenes.data("fourbar")
    d["points"]["A"] = [int("9" * 400), 0]
    with pytest.raises(ValueError) as e:
        pk.Scene.from_dict(d)
    assert one_line(e).startswith("points.A[0] must be a real number within the float range")
    # in a file the number is read as beyond every double: refused as non-finite, by name
    text = json.dumps(pk.scenes.data("fourbar"))
    text = text.replace('"A": [2.0, 0.0]', '"A": [-' + "9" * 400 + ", 0.0]")
    p = write(tmp_path, "big.json", text)
    with pytest.raises(ValueError) as e:
        pk.Scene.load(p)
    assert one_line(e) == f"{p}: points.A: coordinates must be finite, got [-inf, 0.0]"


def test_a_key_given_twice_in_json_names_it_and_its_parent(tmp_path):
    text = json.dumps(pk.scenes.data("fourbar"))
    text = text.replace('"points": {', '"points": {"A": [9, 9], ', 1)
    p = write(tmp_path, "twice.json", text)
    with pytest.raises(ValueError) as e:
        pk.Scene.load(p)
    assert one_line(e) == f"{p}: points.A is given twice (JSON would silently keep the last one)"
    p = write(tmp_path, "top.json", '{"name": "a", "name": "b"}')
    with pytest.raises(ValueError) as e:
        pk.Scene.load(p)
    assert one_line(e).startswith(f"{p}: name is given twice")


def test_a_key_given_twice_in_toml_names_the_file(tmp_path):
    p = write(tmp_path, "twice.toml", 'name = "a"\nname = "b"\n')
    with pytest.raises(ValueError) as e:
        pk.Scene.load(p)
    assert one_line(e).startswith(f"{p}: not valid TOML")


def test_text_that_is_not_json_names_the_file(tmp_path):
    p = write(tmp_path, "cut.json", '{"points": {')
    with pytest.raises(ValueError) as e:
        pk.Scene.load(p)
    assert one_line(e).startswith(f"{p}: not valid JSON: ")


def test_a_scene_error_in_a_file_names_the_file(tmp_path):
    d = pk.scenes.data("fourbar")
    del d["ground"]
    p = write(tmp_path, "noground.json", json.dumps(d))
    with pytest.raises(ValueError) as e:
        pk.Scene.load(p)
    assert one_line(e) == f"{p}: ground: is required"
