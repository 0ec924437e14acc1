"""The README's ``python -c`` one-liners (section "Python") run as written from the
repository root."""

import pathlib
import re
import shlex
import subprocess
import sys

REPO = pathlib.Path(__file__).resolve().parents[2]


def one_liners():
    text = (REPO / "README.md").read_text(encoding="utf-8")
    section = text.split("## Python", 1)[1].split("\n## ", 1)[0]
    return [line for line in section.splitlines() if re.match(r"^python -c ", line)]


def test_readme_one_liners_run():
    lines = one_liners()
    assert len(lines) >= 4
    for line in lines:
        code = shlex.split(line)[2]
        done = subprocess.run(
            [sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True, timeout=120
        )
        assert done.returncode == 0, (line, done.stderr)
        assert done.stdout.strip(), line
