# pip install --no-build-isolation .   (offline: Debian's python3-setuptools, pybind11-dev,
# python3-numpy, cmake and the library's own build dependencies; see README, Python)
#
# setuptools drives CMake: the extension meshsal._meshsal is the CMake target _meshsal
# (python/CMakeLists.txt), built in Release for the interpreter that runs pip, with the
# command-line tool (meshsal/_bin/meshsal, run by the console script `meshsal`) and
# without the tests. Build isolation would fetch setuptools from PyPI, hence
# --no-build-isolation.
import os
import re
import shutil
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
            "-DMESHSAL_BUILD_PYTHON=ON", "-DMESHSAL_BUILD_TESTS=OFF", "-DMESHSAL_BUILD_TOOLS=ON",
            f"-DPython_EXECUTABLE={sys.executable}",
            f"-DMESHSAL_PYTHON_OUTPUT_DIR={out_dir}",
        ]
        if os.environ.get("MESHSAL_WITH_VULKAN") == "OFF":
            configure.append("-DMESHSAL_WITH_VULKAN=OFF")
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(cmake_dir), "--target", "_meshsal", "meshsal_cli", "-j", jobs],
                       check=True)
        # The command-line tool goes into the package; the console script `meshsal` runs it.
        bin_dir = out_dir / "_bin"
        bin_dir.mkdir(parents=True, exist_ok=True)
        shutil.copy2(cmake_dir / "meshsal", bin_dir / "meshsal")


def project_version():
    """The one version: CMakeLists.txt's project(meshsal VERSION X.Y.Z)."""
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(meshsal VERSION ([0-9.]+)", text).group(1)


BUILD.mkdir(exist_ok=True)
setup(
    name="meshsal",
    version=project_version(),
    description="Mesh saliency (Lee, Varshney, Jacobs 2005) over numpy arrays",
    packages=["meshsal"],
    package_dir={"meshsal": "python/meshsal"},
    ext_modules=[CMakeExtension("meshsal._meshsal")],
    cmdclass={"build_ext": CMakeBuild},
    install_requires=["numpy"],
    entry_points={"console_scripts": ["meshsal = meshsal._command:main"]},
    python_requires=">=3.8",
    options={"build": {"build_base": str(BUILD)}, "egg_info": {"egg_base": str(BUILD)}},
    zip_safe=False,
)
