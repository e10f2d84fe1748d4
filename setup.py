"""Builds the compiled module sharpmesh._core with the project's CMake build.

pip runs this through pyproject.toml. The CMake build tree is a folder of
setuptools' build area, or SHARPMESH_CMAKE_BUILD_DIR: an existing build tree
(for example `build` after `make test`) is then reused instead of compiling
everything again. CMake arguments can be added with SHARPMESH_CMAKE_ARGS.
"""
import os
import pathlib
import re
import shlex
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
(ROOT / "build-pip").mkdir(exist_ok=True)


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(sharpmesh VERSION ([0-9.]+)", text).group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = pathlib.Path(os.environ.get("SHARPMESH_CMAKE_BUILD_DIR") or pathlib.Path(self.build_temp) / "cmake").resolve()
        if not (build_dir / "CMakeCache.txt").exists():
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                            "-DSHARPMESH_BUILD_TESTS=OFF", f"-DPython3_EXECUTABLE={sys.executable}",
                            *shlex.split(os.environ.get("SHARPMESH_CMAKE_ARGS", ""))], check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "sharpmesh_python"], check=True)
        built = build_dir / "python" / "sharpmesh"
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve().parent
        target.mkdir(parents=True, exist_ok=True)
        for path in built.iterdir():
            if path.name.startswith("_core") and path.suffix in (".so", ".pyi"):
                self.copy_file(str(path), str(target / path.name))


setup(version=project_version(), ext_modules=[CMakeExtension("sharpmesh._core")], cmdclass={"build_ext": CMakeBuild},
      package_data={"sharpmesh": ["py.typed", "*.pyi"]}, zip_safe=False,
      # setuptools' own build area, apart from the CMake build folder `build`.
      options={"build": {"build_base": "build-pip"}, "egg_info": {"egg_base": "build-pip"}})
