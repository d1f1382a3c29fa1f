"""pip install . : the Python package `sympathy`, its extension built by CMake.

In the manner of pybind11's cmake_example: the pure-Python package comes from python/sympathy,
and the extension `sympathy._core` from the CMake build of this repository (the target
sympathy_python), configured in a directory of its own under the build's temporary directory
(about 4 minutes on two cores: the engine is compiled into it), or taken from an existing CMake
build directory when SYMPATHY_BUILD_DIR names one (built there if out of date: nothing is
compiled twice). With Debian's packages and no network:

    python3 -m venv --system-site-packages ENV
    ENV/bin/pip install --no-build-isolation --no-index .

(build isolation would fetch setuptools from an index). Needs setuptools, cmake, pybind11 and the
engine's Debian packages (scripts/setup); NumPy at run time.
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def version() -> str:
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(sympathy VERSION ([0-9.]+)", f.read()).group(1)


class CMakeExtension(Extension):
    def __init__(self, name: str) -> None:
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        given = os.environ.get("SYMPATHY_BUILD_DIR")
        build = os.path.abspath(given) if given else os.path.join(
            os.path.abspath(self.build_temp), "cmake")
        if not given:
            subprocess.run(["cmake", "-S", ROOT, "-B", build, "-G", "Ninja",
                            "-DCMAKE_BUILD_TYPE=Release", f"-DPython_EXECUTABLE={sys.executable}",
                            "-DSYMPATHY_BUILD_PYTHON=ON"], check=True)
        jobs = str(max(1, os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", build, "--target", "sympathy_python", "-j", jobs],
                       check=True)
        built = [f for f in os.listdir(os.path.join(build, "python", "sympathy"))
                 if f.startswith("_core") and f.endswith(".so")]
        if not built:
            raise RuntimeError(f"no sympathy/_core*.so in {build}/python after the build")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy2(os.path.join(build, "python", "sympathy", built[0]), target)


# setuptools' own build directory (build/lib..., build/temp...) and egg-info go to a temporary
# directory, not into the source tree, whose build/ is CMake's.
scratch = os.path.join(tempfile.gettempdir(), f"sympathy-setup-{os.getuid()}")

setup(
    name="sympathy",
    version=version(),
    description="Periodic orbits, Floquet multipliers, continuation and bifurcations",
    packages=["sympathy"],
    package_dir={"": "python"},
    package_data={"sympathy": ["__init__.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("sympathy._core")],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.11",
    install_requires=["numpy"],
    zip_safe=False,
    options={"build": {"build_base": os.path.join(scratch, "build")},
             "egg_info": {"egg_base": scratch}},
)
