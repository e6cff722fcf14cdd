"""docs/options.md is made from the library's option tables (scripts/option_tables.py): it fails
here when an option was added, renamed or given another default or meaning without the docs."""

import importlib.util
import os

import comic
from conftest import SOURCE_DIR


def load_script():
    path = os.path.join(SOURCE_DIR, "scripts", "option_tables.py")
    spec = importlib.util.spec_from_file_location("option_tables", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_docs_options_is_the_tables_output():
    made = load_script().markdown(comic._core)
    with open(os.path.join(SOURCE_DIR, "docs", "options.md"), encoding="utf-8") as f:
        written = f.read()
    assert written == made, (
        "docs/options.md is not the tables' output: run "
        "PYTHONPATH=build/python python3 scripts/option_tables.py > docs/options.md"
    )


def test_every_table_entry_is_in_the_docs():
    made = load_script().markdown(comic._core)
    for function in ("run_option_table", "tracker_option_table", "detector_option_table"):
        for entry in getattr(comic._core, function)():
            assert "`--%s" % entry["flag"] in made, entry
