"""The ctest python/pip_install: the README's `pip install` line, run as a user on Debian 12 runs it
(Debian's python3 first on PATH, offline, no pip configuration of this machine), with only the
venv's folder moved into a temporary folder, then `import comic` from that venv.

    python3 check_pip_install.py SOURCE_DIR BINARY_DIR VERSION

The line is read from the README (the line starting with `python3 -m venv`), so the test runs what
users are told to type. COMIC_CMAKE_BUILD_DIR points setup.py at the test's configured build tree
(as the ctest python/wheel does), so the build is the module's, not the whole project's again.
Prints "skipped: <why>" when Debian's interpreter or its venv module is missing (the ctest counts
that as skipped, not passed).
"""

import os
import subprocess
import sys
import tempfile

from installed_comic_check import installed_comic_check

DEBIAN_PYTHON = "/usr/bin/python3"


def readme_line(source_dir):
    with open(os.path.join(source_dir, "README.md")) as f:
        lines = [line.strip() for line in f if line.strip().startswith("python3 -m venv")]
    assert len(lines) == 1, "README.md: expected one line starting `python3 -m venv`, got %s" % lines
    return lines[0]


def skip_reason():
    if not os.path.exists(DEBIAN_PYTHON):
        return "no Debian interpreter at %s" % DEBIAN_PYTHON
    for module in ("ensurepip", "venv", "wheel", "setuptools", "numpy"):
        probe = subprocess.run([DEBIAN_PYTHON, "-c", "import " + module], capture_output=True)
        if probe.returncode != 0:
            return "%s has no module %s (scripts/install_deps.sh installs it)" % (
                DEBIAN_PYTHON, module)
    return None


def main(source_dir, binary_dir, version):
    reason = skip_reason()
    if reason:
        print("skipped: " + reason)
        return
    line = readme_line(source_dir)
    assert " .venv " in line + " " and line.endswith(" ."), line
    with tempfile.TemporaryDirectory() as work:
        venv = os.path.join(work, ".venv")
        command = line.replace(".venv", venv)
        # A fresh Debian 12 machine: Debian's python3 first on PATH, pip offline (no index, no
        # links, no configuration file), nothing imported from the build tree.
        env = {
            key: value
            for key, value in os.environ.items()
            if not key.startswith("PIP_") and key not in ("PYTHONPATH", "VIRTUAL_ENV")
        }
        env.update(
            PATH="/usr/bin:/bin:" + env.get("PATH", ""),
            PIP_NO_INDEX="1",
            PIP_NO_CACHE_DIR="1",
            PIP_CONFIG_FILE=os.devnull,
            PIP_DISABLE_PIP_VERSION_CHECK="1",
            COMIC_CMAKE_BUILD_DIR=binary_dir,
        )
        print("running: " + command, flush=True)
        subprocess.check_call(["bash", "-c", command], cwd=source_dir, env=env)
        python = os.path.join(venv, "bin", "python")
        check = installed_comic_check(venv, version, "pip install ok:")
        subprocess.check_call([python, "-c", check], cwd=work, env=env)


if __name__ == "__main__":
    main(*sys.argv[1:4])
