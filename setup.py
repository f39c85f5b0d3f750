"""The one step pyproject.toml cannot declare: the extension module is built by the project's
CMake (tools/python/CMakeLists.txt), never by setuptools, so pip builds the same module as
cmake --build does. GIQ_CMAKE_BUILD_DIR names a configured build folder to reuse."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = Path(os.environ.get("GIQ_CMAKE_BUILD_DIR") or Path(self.build_temp).resolve() / "cmake")
        if not (build / "CMakeCache.txt").exists():
            subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                                   "-DGIQ_BUILD_TESTS=OFF", f"-DPython_EXECUTABLE={sys.executable}"])
        subprocess.check_call(["cmake", "--build", str(build), "--target", "giq_python", "-j", str(os.cpu_count() or 1)])
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        built = build / "python" / "giq" / target.name
        if not built.exists():
            sys.exit(f"setup.py: {built} was not built; is {build} configured for {sys.executable}?")
        shutil.copy2(built, target)
        # Images other than OpenEXR are read through a module loaded on first use, found beside _giq.
        oiio = build / "lib" / "giq-image-oiio.so"
        if oiio.exists():
            shutil.copy2(oiio, target.parent / oiio.name)


setup(ext_modules=[Extension("giq._giq", sources=[])], cmdclass={"build_ext": CMakeBuild})
