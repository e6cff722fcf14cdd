"""Every field of the options structs behind the option tables has a table entry, or is named
here with the door that sets it instead: a field added to ReconstructionRunOptions or
TrackerOptions without a flag and a keyword fails this test. The fields are read from the headers
(the top-level members of each struct); the tables from the built module."""

import os
import re

import comic
from conftest import SOURCE_DIR


def struct_fields(header, struct):
    """The top-level data members of `struct` in `header` (two-space indented declarations)."""
    with open(os.path.join(SOURCE_DIR, header), encoding="utf-8") as f:
        text = f.read()
    body = re.search(r"^struct %s \{\n(.*?)^\};" % struct, text, re.S | re.M).group(1)
    fields = set()
    for line in body.splitlines():
        line = line.split("//")[0]
        m = re.match(
            r"^  (?!using |static |void |friend |struct |enum )[\w:<>, ]+?[\s&*]+(\w+)\s*(=[^;]*)?;",
            line,
        )
        if m and "(" not in line.split("=")[0]:
            fields.add(m.group(1))
    return fields


# The fields a table entry sets through a member of another name.
TRACKER_ENTRY_FIELDS = {
    "search_radius": "matcher",
    "max_cost": "matcher",
    "track_conflicts": "conflict_rule",
    "match_turned": "match_turned_180",
    "max_continued_frames": "continuation",
    "max_alignment_residual": "continuation",
    "aligned_radius": "continuation",
    "min_alignment_correlation": "continuation",
    "alignment_min_eigenvalue": "continuation",
    "bridge_frames": "continuation",
    "alignment_max_fb": "continuation",
    "alignment_iterations": "continuation",
    "alignment_levels": "continuation",
}
# TrackerOptions' fields that are no flag of the apps that track (comic.track's keywords, set up
# by the pairing, or fixed by the tracker's own protocol).
TRACKER_WITHOUT_FLAG = {
    "velocity_neighbours": "comic.track keyword (motion prediction's neighbours)",
    "velocity_neighbour_radius": "comic.track keyword",
    "coarse_factor": "comic.track keyword",
    "coarse_features": "comic.track keyword",
    "verification": "the pairing's (match_verification.h defaults)",
    "min_response": "comic.track keyword (the evaluation's equalised threshold)",
}

RUN_ENTRY_FIELDS = {
    "fixed_intrinsics": "camera",
    "ignore_gt_intrinsics": "camera",
}
# ReconstructionRunOptions' fields that need more than one field, added by each door itself
# (apps/comic_sfm.cc's flags, python/run_keywords.cc's keywords).
RUN_BY_EACH_DOOR = {
    "frames": "the positional FRAMES",
    "detector": "--detector (names checked against the detector factory)",
    "detectors": "--detectors (a list)",
    "detector_options": "the detector's own table (sfm/run/detector_option_table.h)",
    "sequence": "--first, --last, --stride, --resize-height, --max-pixels",
    "camera": "--intrinsics, --camera-model",
    "matching": "--matching",
    "matcher": "--matcher",
    "tracker": "the tracker table (sfm/run/tracker_option_table.h)",
    "threads": "--threads (every app's)",
    "masks": "--masks",
    "mask_drops_nonzero": "--mask-keeps-nonzero (a negation)",
    "regions": "--regions",
    "boundary_band": "--boundary-band (comic_track_eval's too)",
    "output": "--output/-o",
    "colmap": "--colmap-db and its flags",
    "write_frames": "--write-frames[=DIR] (an optional value)",
    "report_page": "the page's limits (no flag)",
}


def test_every_tracker_option_field_has_an_entry_or_a_reason():
    fields = struct_fields("frontend/matching/tracker.h", "TrackerOptions")
    assert {"matcher", "max_features", "continuation", "align_patches"} <= fields
    covered = {TRACKER_ENTRY_FIELDS.get(e["keyword"], e["keyword"])
               for e in comic._core.tracker_option_table()}
    assert covered <= fields, covered - fields
    missing = fields - covered - set(TRACKER_WITHOUT_FLAG)
    assert not missing, "TrackerOptions fields without a table entry: %s" % sorted(missing)


def test_every_run_option_field_has_an_entry_or_a_door():
    fields = struct_fields("sfm/run/run_options.h", "ReconstructionRunOptions")
    assert {"compare", "gt", "init_angle", "tracker"} <= fields
    covered = {RUN_ENTRY_FIELDS.get(e["keyword"], e["keyword"])
               for e in comic._core.run_option_table()}
    assert covered <= fields, covered - fields
    missing = fields - covered - set(RUN_BY_EACH_DOOR)
    assert not missing, "ReconstructionRunOptions fields without a table entry: %s" % sorted(missing)
