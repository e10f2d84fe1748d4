"""The README's Python example runs as written (from the repository root, as
the README says; its page goes to a scratch folder's copy of the tree)."""
import os
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_readme_example_runs_as_written(tmp_path, data):
    readme = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", readme, re.S)
    assert len(blocks) == 1, "the README should hold one Python example"
    (tmp_path / ".cache").mkdir()
    (tmp_path / ".cache" / "data").symlink_to(data.resolve())
    run = subprocess.run([sys.executable, "-c", blocks[0]], cwd=tmp_path, capture_output=True, text=True,
                         env=dict(os.environ), timeout=600)
    assert run.returncode == 0, run.stderr
    facets, lines, hausdorff = re.search(r"^(\d+) facets, (\d+) feature lines, ([0-9.e-]+)$", run.stdout, re.M).groups()
    assert int(facets) > 1000 and int(lines) > 20
    assert float(hausdorff) < 0.02 * 1.4  # fandisk's diagonal is about 1.4: well under 2%
    assert "data-status" in (tmp_path / "fandisk.html").read_text()
