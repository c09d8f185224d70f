"""The README's Python example runs as written, in a fresh interpreter."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

README = Path(__file__).resolve().parents[2] / "README.md"


def python_example() -> str:
    """The first ```python block of the README's ``## Python`` section."""
    text = README.read_text(encoding="utf-8")
    section = text[text.index("\n## Python\n"):]
    match = re.search(r"```python\n(.*?)```", section, re.S)
    assert match, "no ```python block in the README's Python section"
    return match.group(1)


def test_readme_python_example_runs(tmp_path):
    code = python_example()
    assert "import physicskit.classical as pc" in code
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    # Warnings are errors, as in the test suite: the example must not warn either.
    run = subprocess.run([sys.executable, "-W", "error", "-c", code], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    # It prints the result's one-line summary.
    assert run.stdout.startswith("SimulationResult(method='implicit_midpoint', steps=100000")
