"""pip install --no-build-isolation . — the Python module sss (docs/python.md).

The extension is not compiled by setuptools: CMake builds libsss.so and the extension (target
sss_python) exactly as `cmake --build` does, with SSS_PYTHON_WHEEL so that the extension finds the
libsss.so.0 copied next to it. Needs what the CMake build needs (scripts/install-deps.sh) and numpy."""
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(sss VERSION ([0-9.]+)", f.read()).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.path.join(os.path.abspath(self.build_temp), "cmake")
        subprocess.check_call(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                               "-DSSS_BUILD_TESTS=OFF", "-DSSS_BUILD_EXAMPLES=OFF", "-DSSS_WERROR=OFF",
                               "-DSSS_PYTHON=ON", "-DSSS_PYTHON_WHEEL=ON", "-DPython3_EXECUTABLE=" + sys.executable])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.check_call(["cmake", "--build", build, "--target", "sss_python", "-j", jobs])
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        built = os.path.join(build, "python", "sss")
        module = [f for f in os.listdir(built) if f.startswith("_sss.") and f.endswith(".so")]
        if len(module) != 1:
            raise RuntimeError("%s: expected one _sss*.so, found %s" % (built, module))
        shutil.copyfile(os.path.join(built, module[0]), target)
        shutil.copyfile(os.path.join(build, "libsss.so.0"), os.path.join(os.path.dirname(target), "libsss.so.0"))


setup(
    name="sss",
    version=project_version(),
    description="Real-time subsurface scattering and its CPU ground truth (numpy images)",
    packages=["sss"],
    package_dir={"": "python"},
    ext_modules=[Extension("sss._sss", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    install_requires=["numpy"],
    python_requires=">=3.8",
)
