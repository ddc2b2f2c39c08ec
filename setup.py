# pip install --no-build-isolation .   (offline: Debian's python3-setuptools, pybind11-dev,
# python3-numpy, cmake and the library's own build dependencies; see README, Python)
#
# setuptools drives CMake: the extension meshsal._meshsal is the CMake target _meshsal
# (python/CMakeLists.txt), built in Release for the interpreter that runs pip, without the
# CLI and the tests. Build isolation would fetch setuptools from PyPI, hence
# --no-build-isolation.
import os
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
BUILD = ROOT / "build-python"  # setuptools' and CMake's scratch space (ignored by git)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        out_dir = Path(self.get_ext_fullpath(ext.name)).resolve().parent
        cmake_dir = BUILD / "cmake"
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(cmake_dir),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DMESHSAL_BUILD_PYTHON=ON", "-DMESHSAL_BUILD_TESTS=OFF", "-DMESHSAL_BUILD_TOOLS=OFF",
            f"-DPython_EXECUTABLE={sys.executable}",
            f"-DMESHSAL_PYTHON_OUTPUT_DIR={out_dir}",
        ]
        if os.environ.get("MESHSAL_WITH_VULKAN") == "OFF":
            configure.append("-DMESHSAL_WITH_VULKAN=OFF")
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(cmake_dir), "--target", "_meshsal", "-j", jobs], check=True)


BUILD.mkdir(exist_ok=True)
setup(
    name="meshsal",
    version="0.2.0",
    description="Mesh saliency (Lee, Varshney, Jacobs 2005) over numpy arrays",
    packages=["meshsal"],
    package_dir={"meshsal": "python/meshsal"},
    ext_modules=[CMakeExtension("meshsal._meshsal")],
    cmdclass={"build_ext": CMakeBuild},
    install_requires=["numpy"],
    python_requires=">=3.8",
    options={"build": {"build_base": str(BUILD)}, "egg_info": {"egg_base": str(BUILD)}},
    zip_safe=False,
)
