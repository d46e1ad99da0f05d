# SPDX-License-Identifier: MIT
"""Builds the extension calder._calder with CMake (python/CMakeLists.txt).

Used by `pip install --no-build-isolation .`: the module is built for the
Python that runs pip (the venv's), against Debian's pybind11 (pybind11-dev).
Set CMAKE_BUILD_PARALLEL_LEVEL to change the number of compile jobs.
"""

import json
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def python_preset_options():
    """The cache variables of CMakePresets.json's "python" preset: pip builds
    what `cmake --preset python` builds, with the same components off."""
    presets = json.loads((ROOT / "CMakePresets.json").read_text())
    for preset in presets["configurePresets"]:
        if preset["name"] == "python":
            return preset["cacheVariables"]
    raise RuntimeError("setup.py: CMakePresets.json has no configure preset named python")


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = pathlib.Path(self.build_temp).resolve() / "cmake"
        configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir)]
        configure += [f"-D{name}={value}" for name, value in python_preset_options().items()]
        configure += ["-DCALDER_WARNINGS_AS_ERRORS=OFF", f"-DPython_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja") and not (build_dir / "CMakeCache.txt").exists():
            configure += ["-G", "Ninja"]
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 2))
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "calder_python",
                        "--parallel", jobs], check=True)
        built = list((build_dir / "python" / "calder").glob("_calder*.so"))
        if len(built) != 1:
            raise RuntimeError(f"setup.py: expected one built module, found {built}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


# setuptools' build folder and metadata stay out of the way of CMake's build/.
(ROOT / "build-pip").mkdir(exist_ok=True)

setup(
    packages=["calder"],
    package_dir={"calder": "python/calder"},
    package_data={"calder": ["*.pyi", "py.typed"]},
    ext_modules=[Extension("calder._calder", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-pip"}, "egg_info": {"egg_base": "build-pip"}},
)
