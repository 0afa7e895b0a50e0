"""Builds the compiled core of the Python package with CMake: the repository's
CMakeLists.txt, target fastnorm_python, for the interpreter that runs pip. The pure-Python
files come from src/fastnorm; the version from include/fastnorm/version.hpp."""

import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent  # the repository: pip builds in place


def version():
    text = (ROOT / "include" / "fastnorm" / "version.hpp").read_text()
    parts = [re.search(rf"#define FASTNORM_VERSION_{part} (\d+)", text).group(1) for part in ("MAJOR", "MINOR", "PATCH")]
    return ".".join(parts)


class BuildWithCMake(build_py):
    """The pure-Python files, then _fastnorm built by CMake beside them."""

    def run(self):
        super().run()
        build_dir = pathlib.Path(self.get_finalized_command("build").build_temp).resolve() / "cmake"
        configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                     "-DFASTNORM_PYTHON=ON", "-DFASTNORM_BUILD_TESTS=OFF", "-DFASTNORM_INSTALL=OFF",
                     f"-DPython_EXECUTABLE={sys.executable}"]
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "fastnorm_python", "--parallel"], check=True)
        built = list((build_dir / "python" / "fastnorm").glob("_fastnorm*.so"))
        if len(built) != 1:
            raise RuntimeError(f"fastnorm: expected one compiled module in {build_dir}, found {built}")
        target = pathlib.Path(self.build_lib) / "fastnorm"
        target.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target / built[0].name)


class BinaryDistribution(Distribution):
    """A wheel for this platform and interpreter: it holds a compiled module."""

    def has_ext_modules(self):
        return True


setup(version=version(), cmdclass={"build_py": BuildWithCMake}, distclass=BinaryDistribution)
