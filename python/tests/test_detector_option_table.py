"""The library's detector option table (sfm/run/detector_option_table.h) reaches both doors: each
entry is a flag in comic_detect --help, a keyword detect() accepts for the searches it names with
its type checked, and a paragraph of detect()'s docstring."""

import re
import subprocess

import numpy as np
import pytest

import comic
from conftest import app

TABLE = comic._core.detector_option_table()
IMAGE = np.full((40, 40), 128, np.uint8)


def test_every_entry_is_a_flag_of_comic_detect():
    help_text = subprocess.run(
        [app("comic_detect"), "--help"], stdout=subprocess.PIPE, text=True, check=True
    ).stdout
    flags = set(re.findall(r"^  (?:-\w, )?--([a-z0-9-]+)", help_text, re.MULTILINE))
    assert len(TABLE) >= 18
    assert not {entry["flag"] for entry in TABLE} - flags


def test_every_entry_is_in_the_docstring():
    for entry in TABLE:
        assert re.search(r"\b%s\b" % entry["keyword"], comic.detect.__doc__), entry


@pytest.mark.parametrize("entry", TABLE, ids=[entry["keyword"] for entry in TABLE])
def test_keyword_is_accepted_and_typed(entry):
    keyword, default = entry["keyword"], entry["default"]
    for detector in ("comic", "comic-paper"):
        if detector not in entry["detectors"]:
            with pytest.raises(ValueError, match="unknown option '%s'" % keyword):
                comic.detect(IMAGE, detector, **{keyword: default})
            continue
        comic.detect(IMAGE, detector, **{keyword: default})
        # A bool is refused for a number and a number for a bool.
        wrong = 1 if isinstance(default, bool) else True
        with pytest.raises(TypeError, match=keyword):
            comic.detect(IMAGE, detector, **{keyword: wrong})
