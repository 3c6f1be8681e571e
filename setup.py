"""pip install . --no-build-isolation: builds the Python module with the
project's CMake build (Release, without tests and benchmarks) and installs
the package impactlab. Needs no network (Debian's setuptools, pybind11-dev)."""
import os
import pathlib
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, extension):
        target_dir = pathlib.Path(self.get_ext_fullpath(extension.name)).resolve().parent
        build_dir = pathlib.Path(self.build_temp).resolve() / "cmake"
        build_dir.mkdir(parents=True, exist_ok=True)
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build_dir),
                        "-DCMAKE_BUILD_TYPE=Release", "-DIMPACTLAB_BUILD_TESTS=OFF",
                        "-DIMPACTLAB_BUILD_BENCHMARKS=OFF", "-DIMPACTLAB_BUILD_PYTHON=ON",
                        "-DPython3_EXECUTABLE=" + sys.executable,
                        "-DPYTHON_EXECUTABLE=" + sys.executable], check=True)
        jobs = str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "_impactlab", "-j", jobs],
                       check=True)
        built = next((build_dir / "python" / "impactlab").glob("_impactlab*.so"))
        target_dir.mkdir(parents=True, exist_ok=True)
        self.copy_file(str(built), str(target_dir / built.name))


class WithFigures(build_py):
    """Puts the plot scripts' drawing functions (scripts/plot_*.py) into the
    package impactlab.figures, as the CMake build does, so that a result's
    plot() draws with the CLI's code."""

    def run(self):
        super().run()
        target = pathlib.Path(self.build_lib) / "impactlab" / "figures"
        target.mkdir(parents=True, exist_ok=True)
        for script in sorted((ROOT / "scripts").glob("plot_*.py")):
            self.copy_file(str(script), str(target / script.name))


setup(
    name="impactlab",
    version="0.1.0",
    description="Impact oscillators: event-driven simulation, sections, sweeps, Floquet analysis",
    packages=["impactlab", "impactlab.figures"],
    package_dir={"": "python"},
    ext_modules=[CMakeExtension("impactlab._impactlab")],
    cmdclass={"build_ext": CMakeBuild, "build_py": WithFigures},
    install_requires=["numpy"],
    python_requires=">=3.9",
    zip_safe=False,
)
