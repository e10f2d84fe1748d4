#!/usr/bin/env bash
# `pip install .` as a user runs it on Debian: into a fresh virtual environment
# that sees Debian's numpy (--system-site-packages), offline, reusing the
# CMake build tree so the library is not compiled twice. Then the README's
# Python example runs with that environment's interpreter, outside the
# repository, and the installed package carries its type stub.
# usage: pip_install_test.sh BUILD_DIR SOURCE_DIR DATA_DIR
set -euo pipefail
build=$(realpath "$1") source=$(realpath "$2") data=$(realpath "$3")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$work/env"
SHARPMESH_CMAKE_BUILD_DIR="$build" "$work/env/bin/pip" install --no-build-isolation --no-index -q "$source"
mkdir -p "$work/run/.cache"
ln -s "$data" "$work/run/.cache/data"
cd "$work/run"
"$work/env/bin/python" - "$source/README.md" <<'PY'
import pathlib, re, subprocess, sys
import sharpmesh
package = pathlib.Path(sharpmesh.__file__).parent
assert "site-packages" in str(package), package
from importlib.metadata import version
assert sharpmesh.__version__ == version("sharpmesh"), (sharpmesh.__version__, version("sharpmesh"))
assert (package / "_core.pyi").is_file() and (package / "py.typed").is_file(), sorted(p.name for p in package.iterdir())
blocks = re.findall(r"```python\n(.*?)```", pathlib.Path(sys.argv[1]).read_text(), re.S)
assert len(blocks) == 1, "the README should hold one Python example"
run = subprocess.run([sys.executable, "-c", blocks[0]], capture_output=True, text=True, timeout=600)
assert run.returncode == 0, run.stderr
assert re.search(r"^\d+ facets, \d+ feature lines, ", run.stdout, re.M), run.stdout
assert pathlib.Path("fandisk.html").is_file()
PY
