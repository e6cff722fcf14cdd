"""The compiled half of the Python module `comic` (comic._core), built by the project's CMake.

pyproject.toml holds the metadata; this file only teaches setuptools' build_ext to configure the
project with CMake (tests off, Release, the interpreter that runs the build) and build the target
comic_python, then to copy the module it made into the wheel. The version is CMake's
project(VERSION). COMIC_CMAKE_BUILD_DIR names a configured build tree to build in instead of a
fresh one (the ctest python/wheel uses the test's own tree)."""

import glob
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE_DIR = os.path.dirname(os.path.abspath(__file__))
# setuptools' own files go under build/setuptools/, beside a CMake build/ tree, never into python/.
SETUPTOOLS_DIR = os.path.join("build", "setuptools")


def cmake_version():
    with open(os.path.join(SOURCE_DIR, "CMakeLists.txt")) as f:
        match = re.search(r"project\(\s*comic_sfm\s+VERSION\s+([0-9.]+)", f.read())
    if not match:
        sys.exit("setup.py: no project(comic_sfm VERSION x.y.z) in CMakeLists.txt")
    return match.group(1)


class CMakeBuild(build_ext):
    """Builds comic._core with CMake instead of compiling sources itself."""

    def build_extension(self, ext):
        build_dir = os.environ.get("COMIC_CMAKE_BUILD_DIR") or os.path.join(
            os.path.abspath(self.build_temp), "cmake"
        )
        if not os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
            configure = [
                "cmake", "-S", SOURCE_DIR, "-B", build_dir,
                "-DCMAKE_BUILD_TYPE=Release",
                "-DCOMIC_BUILD_TESTS=OFF",
                "-DPython3_EXECUTABLE=" + sys.executable,
            ]
            if shutil.which("ccache"):
                configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
            subprocess.check_call(configure)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.check_call(
            ["cmake", "--build", build_dir, "--target", "comic_python", "-j", jobs]
        )
        built = glob.glob(os.path.join(build_dir, "python", "comic", "_core*.so"))
        if len(built) != 1:
            sys.exit("setup.py: expected one comic/_core*.so in %s, found %s" % (build_dir, built))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)


os.makedirs(SETUPTOOLS_DIR, exist_ok=True)
setup(
    version=cmake_version(),
    ext_modules=[Extension("comic._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": SETUPTOOLS_DIR}, "egg_info": {"egg_base": SETUPTOOLS_DIR}},
)
