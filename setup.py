# The build step of `pip install .` (pyproject.toml): CMake configures and builds the extension smcbench._smcbench
# and the command-line program (python/CMakeLists.txt, target smcbench_python_cli) and setuptools packages them
# with python/smcbench/*.py and the data folders (share/smcbench/{scenes,siconos}, found by the module relative to
# itself: problems/io/data_dirs.h). The program lands in smcbench/bin/smcbench; the console command `smcbench` and
# `python -m smcbench` run it (python/smcbench/__main__.py).
#
# Environment:
#   SMCBENCH_BUILD_DIR   the CMake build tree (default build/pip in this checkout, kept, so a reinstall rebuilds
#                        only what changed). A tree that is already configured (build/release) is only built, never
#                        re-configured.
#   SMCBENCH_CMAKE_ARGS  extra arguments of the first configure (e.g. -DSMCBENCH_WERROR=ON).
#   CMAKE_CXX_COMPILER_LAUNCHER (ccache), CMAKE_GENERATOR: read by CMake at the first configure.
#   CMAKE_BUILD_PARALLEL_LEVEL: the build's jobs (default: the number of processors).
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE_DIR = os.path.dirname(os.path.abspath(__file__))


def project_version():
    """The version of project(smcbench VERSION x.y.z) in CMakeLists.txt: one version for C++ and Python."""
    with open(os.path.join(SOURCE_DIR, "CMakeLists.txt"), encoding="utf-8") as f:
        match = re.search(r"project\(smcbench VERSION ([0-9.]+)", f.read())
    if not match:
        raise RuntimeError("setup.py: no 'project(smcbench VERSION x.y.z)' in CMakeLists.txt")
    return match.group(1)


def data_files():
    """share/smcbench/scenes and share/smcbench/siconos, laid out as cmake --install lays them out."""
    folders = {"share/smcbench/scenes": sorted(glob.glob("problems/scenes/*.json"))}
    collection = "tests/data/siconos"
    for root, _, files in sorted(os.walk(collection)):
        target = "share/smcbench/siconos" + root[len(collection):]
        folders[target] = sorted(os.path.join(root, f) for f in files)
    return [(target, files) for target, files in folders.items() if files]


class CMakeBuild(build_ext):
    """Builds the extension with CMake instead of compiling its (empty) source list."""

    def build_extension(self, ext):
        build_dir = os.path.abspath(os.environ.get("SMCBENCH_BUILD_DIR") or os.path.join(SOURCE_DIR, "build", "pip"))
        if not os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")):
            # The real interpreter, not the virtual environment's link to it: the module's ABI is the interpreter's,
            # and the cached path stays valid when the environment is deleted.
            configure = ["cmake", "-S", SOURCE_DIR, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                         "-DSMCBENCH_BUILD_PYTHON=ON", "-DSMCBENCH_BUILD_TESTS=OFF",
                         "-DSMCBENCH_BUILD_BENCHMARKS=OFF",
                         "-DPython_EXECUTABLE=" + os.path.realpath(sys.executable)]
            configure += shlex.split(os.environ.get("SMCBENCH_CMAKE_ARGS", ""))
            subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", build_dir, "--target", "_smcbench", "smcbench_python_cli", "--parallel",
                        jobs], check=True)

        # The module CMake built for this interpreter (its file name carries the ABI: .cpython-311-x86_64-...so).
        built = os.path.join(build_dir, "python", "smcbench", "_smcbench" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not os.path.isfile(built):
            found = glob.glob(os.path.join(build_dir, "python", "smcbench", "_smcbench*"))
            raise RuntimeError(f"setup.py: {built} was not built (found: {found or 'nothing'}); the build tree "
                               f"{build_dir} is configured for another Python or without SMCBENCH_BUILD_PYTHON")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)
        self.copy_program(build_dir, os.path.dirname(target))

    def copy_program(self, build_dir, package_dir):
        """The command-line program into the package (smcbench/bin/smcbench, executable): the file the build tree's
        link python/smcbench/bin/smcbench points to."""
        program = os.path.join(build_dir, "python", "smcbench", "bin", "smcbench")
        if not os.path.isfile(program):
            raise RuntimeError(f"setup.py: {program} was not built (target smcbench_python_cli)")
        target = os.path.join(package_dir, "bin", "smcbench")
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(os.path.realpath(program), target)
        os.chmod(target, 0o755)


os.chdir(SOURCE_DIR)  # data_files and package_dir are relative to this folder
setup(
    version=project_version(),
    packages=["smcbench"],
    package_dir={"": "python"},
    ext_modules=[Extension("smcbench._smcbench", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    data_files=data_files(),
    zip_safe=False,
)
