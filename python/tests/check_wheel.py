"""The ctest python/wheel: builds the wheel as docs/packaging.md says (Debian's pip, setuptools and
wheel, offline, --no-build-isolation), in the test's own CMake tree (COMIC_CMAKE_BUILD_DIR), then
checks what it holds, installs it into a temporary folder and imports it from there.

    python3 check_wheel.py SOURCE_DIR BINARY_DIR VERSION
"""

import glob
import os
import subprocess
import sys
import tempfile
import zipfile

from installed_comic_check import installed_comic_check


def main(source_dir, binary_dir, version):
    with tempfile.TemporaryDirectory() as work:
        env = dict(os.environ, COMIC_CMAKE_BUILD_DIR=binary_dir, PIP_NO_INDEX="1")
        env.pop("PYTHONPATH", None)  # the wheel, not the build tree, must be imported
        pip = [sys.executable, "-m", "pip", "--disable-pip-version-check", "--no-cache-dir"]
        subprocess.check_call(
            pip + ["wheel", "--no-build-isolation", "--no-deps", "-w", work, source_dir],
            cwd=source_dir,
            env=env,
        )
        wheels = glob.glob(os.path.join(work, "comic_sfm-%s-*.whl" % version))
        assert len(wheels) == 1, "expected one comic_sfm-%s wheel, got %s" % (version, wheels)
        names = zipfile.ZipFile(wheels[0]).namelist()
        assert "comic/__init__.py" in names, names
        assert any(n.startswith("comic/_core") and n.endswith(".so") for n in names), names

        site = os.path.join(work, "site")
        subprocess.check_call(
            pip + ["install", "--no-deps", "--no-index", "--target", site, wheels[0]], env=env
        )
        check = installed_comic_check(site, version, "wheel ok:")
        subprocess.check_call([sys.executable, "-c", check], env=dict(env, PYTHONPATH=site), cwd=work)


if __name__ == "__main__":
    main(*sys.argv[1:4])
