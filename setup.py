"""setuptools builds the Python package through the project's CMake build:
the compiled core (_core) goes into the package beside its Python files,
and the `barimpact` command into the environment's bin/ (it finds the
package beside itself, in ../lib/pythonX.Y/site-packages)."""
import os
import re
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from distutils.command.build_scripts import build_scripts  # setuptools uses distutils' own

ROOT = Path(__file__).resolve().parent
VERSION = re.search(r"project\(barimpact VERSION (\S+)", (ROOT / "CMakeLists.txt").read_text()).group(1)


class CMakeExtension(Extension):
    """The pybind11 module, built by CMake rather than by setuptools."""

    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = Path(self.build_temp).resolve() / "cmake"
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                     "-DBARIMPACT_BUILD_TESTS=OFF", "-DBARIMPACT_BUILD_BENCH=OFF",
                     f"-DBARIMPACT_PYTHON={sys.executable}"]
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build), "-j", jobs, "--target", "barimpact_python", "barimpact_cli"],
                       check=True)
        core = next((build / "python" / "barimpact").glob("_core*.so"))
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        self.copy_file(str(core), str(target))
        # The command, for build_scripts (which runs after build_ext).
        scripts = Path(self.build_temp).resolve() / "scripts"
        scripts.mkdir(parents=True, exist_ok=True)
        self.copy_file(str(build / "barimpact"), str(scripts / "barimpact"))
        self.distribution.scripts = [str(scripts / "barimpact")]  # read when build_scripts is finalized


class CopyCommand(build_scripts):
    """The command is a compiled program: copied as it is (build_scripts
    would read it as a Python script to rewrite its first line)."""

    def copy_scripts(self):
        self.mkpath(self.build_dir)
        outfiles = []
        for script in self.scripts:
            target = os.path.join(self.build_dir, os.path.basename(script))
            self.copy_file(script, target)
            os.chmod(target, 0o755)
            outfiles.append(target)
        return outfiles, outfiles


setup(
    version=VERSION,
    packages=["barimpact"],
    package_dir={"": "python"},
    package_data={"barimpact": ["*.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("barimpact._core")],
    cmdclass={"build_ext": CMakeBuild, "build_scripts": CopyCommand},
    zip_safe=False,
)
