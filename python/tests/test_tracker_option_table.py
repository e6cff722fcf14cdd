"""The library's tracker table (sfm/run/tracker_option_table.h) reaches every door: each entry is
a flag of comic_sfm and comic_export_colmap, a keyword of reconstruct(), export_colmap() and
track() with its type checked, a paragraph of reconstruct()'s docstring, and a key of report.json's
options."""

import re
import subprocess

import numpy as np
import pytest

import comic
from conftest import app

TABLE = comic._core.tracker_option_table()
FRAMES = [np.full((40, 40), 128, np.uint8)] * 2


def long_flags(name):
    help_text = subprocess.run(
        [app(name), "--help"], stdout=subprocess.PIPE, text=True, check=True
    ).stdout
    return set(re.findall(r"^  (?:-\w, )?--([a-z0-9-]+)", help_text, re.MULTILINE))


@pytest.mark.parametrize("name", ["comic_sfm", "comic_export_colmap", "comic_track_survival"])
def test_every_entry_is_a_flag(name):
    assert len(TABLE) == 21
    assert not {entry["flag"] for entry in TABLE} - long_flags(name)


def test_every_entry_is_a_keyword_of_each_door():
    keywords = [entry["keyword"] for entry in TABLE]
    assert list(comic.TRACKER_OPTIONS) == keywords
    assert not set(keywords) - set(comic.RECONSTRUCT_OPTIONS)
    assert not set(keywords) - set(comic.EXPORT_COLMAP_OPTIONS)
    for entry in TABLE:
        assert re.search(r"\b%s\b" % entry["keyword"], comic.reconstruct.__doc__), entry
        assert re.search(r"\b%s\b" % entry["keyword"], comic.export_colmap.__doc__), entry


@pytest.mark.parametrize("entry", TABLE, ids=[entry["keyword"] for entry in TABLE])
def test_keyword_is_typed(entry):
    # A bool is refused for a number, a number for a bool, and a number for a name.
    default = entry["default"]
    wrong = 1 if isinstance(default, (bool, str)) else True
    with pytest.raises(TypeError, match=entry["keyword"]):
        comic.track(FRAMES, "harris", **{entry["keyword"]: wrong})


def test_a_bad_name_is_a_value_error_naming_the_flag():
    with pytest.raises(ValueError, match="prediction"):
        comic.track(FRAMES, "harris", prediction="psychic")


def test_report_echoes_every_entry_as_resolved(example, tmp_path):
    run = comic.reconstruct(
        example + "/image_l", last=5, search_radius=31.0, align_patches=False, quiet=True
    )
    options = run.report["options"]
    for entry in TABLE:
        assert entry["keyword"] in options, entry
    assert options["search_radius"] == 31.0
    assert options["align_patches"] is False
