"""The library's table of plain run options (sfm/run/run_option_table.h) reaches both doors:
each entry is a flag in comic_sfm --help, a keyword reconstruct() accepts with its type checked,
and a paragraph of reconstruct()'s docstring."""

import re
import subprocess

import pytest

import comic
from conftest import app

TABLE = comic._core.run_option_table()


def help_flags():
    help_text = subprocess.run(
        [app("comic_sfm"), "--help"], stdout=subprocess.PIPE, text=True, check=True
    ).stdout
    return set(re.findall(r"^  (?:-\w, )?--([a-z0-9-]+)", help_text, re.MULTILINE))


def test_table_is_not_empty():
    assert len(TABLE) > 20


def test_every_entry_is_a_flag_of_comic_sfm():
    missing = {entry["flag"] for entry in TABLE} - help_flags()
    assert not missing


def test_every_entry_is_a_keyword_of_reconstruct():
    missing = {entry["keyword"] for entry in TABLE} - set(comic.RECONSTRUCT_OPTIONS)
    assert not missing


def test_every_entry_is_in_the_docstring():
    for entry in TABLE:
        assert re.search(r"\b%s\b" % entry["keyword"], comic.reconstruct.__doc__), entry


@pytest.mark.parametrize("entry", TABLE, ids=[entry["keyword"] for entry in TABLE])
def test_keyword_is_accepted_and_typed(entry):
    keyword, default = entry["keyword"], entry["default"]
    # The default passes every check; the missing frames are then the only trouble.
    with pytest.raises(RuntimeError, match="no such file or folder"):
        comic.reconstruct("/nonexistent/frames", **{keyword: default})
    # A bool is refused for a number and a number for a bool; a str wants a str.
    wrong = 1 if isinstance(default, (bool, str)) else True
    with pytest.raises(TypeError, match=keyword):
        comic.reconstruct("/nonexistent/frames", **{keyword: wrong})
