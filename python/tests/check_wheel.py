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
        check = (
            "import comic, numpy\n"
            "assert comic.__file__.startswith(%r), comic.__file__\n"
            "assert comic.__version__ == %r, comic.__version__\n"
            "image = numpy.full((60, 60), 40, numpy.uint8)\n"
            "image[20:40, 20:40] = 200\n"
            "features, _ = comic.detect(image, detector='harris')\n"
            "assert len(features) >= 4, len(features)\n"
            "print('wheel ok:', comic.__file__, comic.__version__, len(features), 'features')\n"
        ) % (site, version)
        subprocess.check_call([sys.executable, "-c", check], env=dict(env, PYTHONPATH=site), cwd=work)


if __name__ == "__main__":
    main(*sys.argv[1:4])
