#!/usr/bin/env python3
"""Writes docs/options.md from the library's option tables (sfm/run/run_option_table.h,
sfm/run/tracker_option_table.h, sfm/run/detector_option_table.h), through the built Python module,
so that the docs' option tables are made from what the apps' --help and the Python keywords are
made from. The pytest test_option_docs.py fails when docs/options.md differs from its output.

  PYTHONPATH=build/python python3 scripts/option_tables.py > docs/options.md
"""

import sys

HEADER = """# Options

Made by `scripts/option_tables.py` from the library's option tables, the tables every door reads:
each entry is a long flag of the apps named, a keyword of the Python functions named (the flag
with `_` for `-`), and a paragraph of their `--help` and docstrings. Do not edit by hand: run
`PYTHONPATH=build/python python3 scripts/option_tables.py > docs/options.md` (the ctest
`python/pytest` checks that this file is its output). The options that need more than one field
(`--detector`, `--intrinsics`, `--masks`, the frame range, the outputs) are listed by
`comic_sfm --help` and in [apps.md](apps.md).
"""

FAMILIES = [
    (
        "The run",
        "run_option_table",
        "`comic_sfm`; Python `comic.reconstruct`",
        "sfm/run/run_option_table.h",
    ),
    (
        "The tracker",
        "tracker_option_table",
        "`comic_sfm`, `comic_export_colmap`, `comic_render_eval` (the run's default) and "
        "`comic_track_survival`; Python `comic.reconstruct`, `comic.export_colmap` and "
        "`comic.track` (whose defaults are the paper's protocol: no prediction, 20 px, every "
        "feature)",
        "sfm/run/tracker_option_table.h",
    ),
    (
        "CoMIC's detector",
        "detector_option_table",
        "`comic_detect`; Python `comic.detect` and every `detector_options`",
        "sfm/run/detector_option_table.h",
    ),
]


def default_text(value):
    if isinstance(value, bool):
        return "on" if value else "off"
    if value == "":
        return "(none)"
    return str(value)


def cell(text):
    return str(text).replace("|", "\\|")


def markdown(core):
    lines = [HEADER]
    for title, function, doors, header in FAMILIES:
        lines += ["## %s" % title, "", "Doors: %s. The table: `%s`." % (doors, header), ""]
        searches = function == "detector_option_table"
        columns = ["flag", "keyword", "default"] + (["searches"] if searches else []) + ["meaning"]
        lines += ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
        for entry in getattr(core, function)():
            flag = "`--%s%s`" % (entry["flag"], " " + entry["metavar"] if entry["metavar"] else "")
            row = [flag, "`%s`" % entry["keyword"], cell(default_text(entry["default"]))]
            if searches:
                row.append(", ".join(entry["detectors"]))
            row.append(cell(entry["help"]))
            lines.append("| " + " | ".join(row) + " |")
        lines.append("")
    return "\n".join(lines)


def main():
    import comic  # the built module: PYTHONPATH=build/python

    sys.stdout.write(markdown(comic._core))


if __name__ == "__main__":
    main()
