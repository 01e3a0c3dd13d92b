"""setuptools builds the Python package through the project's CMake build:
the compiled core (_core) goes into the package beside its Python files,
and the `barimpact` command into the environment's bin/ (it finds the
package beside itself, in ../lib/pythonX.Y/site-packages).

It packages an existing build tree of this source when there is one it
can use: the one BARIMPACT_CMAKE_BUILD_DIR names, else build/release (what
`make demo` builds) or build/ci, if configured for the same Python and not
instrumented. It brings that tree's module and command up to date and
packages them without compiling the library again (minutes saved). Else,
or with BARIMPACT_CMAKE_BUILD_DIR set empty, it configures and builds a
CMake build of its own (Release)."""
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


def build_problems(build):
    """Why a build tree's module and command are not what a build of its own
    would package ([] if they are): configured from this source tree, for
    this interpreter (the module's ABI, where the command looks for the
    package), with the module and without instrumentation (a sanitized or
    fuzzing _core cannot be imported by a plain Python)."""
    try:
        lines = (build / "CMakeCache.txt").read_text().splitlines()
    except OSError:
        return ["not a CMake build tree (no CMakeCache.txt)"]
    cache = dict(m.groups() for m in map(re.compile(r"(\w+):\w+=(.*)").fullmatch, lines) if m)

    def on(option):
        return cache.get(option, "OFF").upper() in ("1", "ON", "YES", "TRUE", "Y")

    problems = []
    if Path(cache.get("CMAKE_HOME_DIRECTORY", "")).resolve() != ROOT:
        problems.append(f"configured from {cache.get('CMAKE_HOME_DIRECTORY')}, not from {ROOT}")
    if Path(cache.get("BARIMPACT_PYTHON", "")).resolve() != Path(sys.executable).resolve():
        problems.append(f"configured for {cache.get('BARIMPACT_PYTHON')}, not for this Python ({sys.executable})")
    if not on("BARIMPACT_BUILD_PYTHON"):
        problems.append("BARIMPACT_BUILD_PYTHON is OFF")
    if cache.get("CMAKE_BUILD_TYPE", "") != "Release":
        problems.append(f"CMAKE_BUILD_TYPE is {cache.get('CMAKE_BUILD_TYPE') or 'unset'}, not Release")
    return problems + [f"{option} is ON" for option in ("BARIMPACT_SANITIZE", "BARIMPACT_FUZZ") if on(option)]


def existing_build():
    """The build tree to package: BARIMPACT_CMAKE_BUILD_DIR's (refused with
    its problems), else build/release or build/ci when usable; None: none."""
    named = os.environ.get("BARIMPACT_CMAKE_BUILD_DIR")
    if named:
        build = Path(named).resolve()
        problems = build_problems(build)
        if problems:
            sys.exit(f"BARIMPACT_CMAKE_BUILD_DIR={build} cannot be packaged: " + "; ".join(problems))
        return build
    if named is not None:  # set empty: a build of its own
        return None
    for build in (ROOT / "build" / "release", ROOT / "build" / "ci"):
        if build.is_dir() and not build_problems(build):
            print(f"barimpact: packaging the existing build {build} (BARIMPACT_CMAKE_BUILD_DIR= for a build of its own)")
            return build
    return None


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        build = existing_build()
        if build is None:
            build = Path(self.build_temp).resolve() / "cmake"
            configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                         "-DBARIMPACT_BUILD_TESTS=OFF", "-DBARIMPACT_BUILD_BENCH=OFF",
                         f"-DBARIMPACT_PYTHON={sys.executable}"]
            subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build), "-j", jobs, "--target", "barimpact_python", "barimpact_cli",
                        "barimpact_hdf5_module", "barimpact_fit_module"], check=True)
        core = next((build / "python" / "barimpact").glob("_core*.so"))
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        self.copy_file(str(core), str(target))
        # results.h5's HDF5 module and signal matching's fitting module, which the
        # library looks for beside the package's _core.
        for pattern in ("libbarimpact_hdf5.so.*", "libbarimpact_fit.so.*"):
            for module in (build / "python" / "barimpact").glob(pattern):
                self.copy_file(str(module), str(target.parent))
        # The command, for build_scripts (which runs after build_ext).
        scripts = Path(self.build_temp).resolve() / "scripts"
        scripts.mkdir(parents=True, exist_ok=True)
        # With MPI, its build of the command too, which `barimpact sweep` runs under mpirun.
        commands = [name for name in ("barimpact", "barimpact-mpi") if (build / name).exists()]
        for name in commands:
            self.copy_file(str(build / name), str(scripts / name))
        self.distribution.scripts = [str(scripts / name) for name in commands]  # read when build_scripts is finalized


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
