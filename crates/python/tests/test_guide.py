"""The user guide's Python blocks run (docs/guide/src): every ```python block of a chapter runs,
in order and in one namespace, from a working folder that holds a link to the repository's
fixtures, so that the guide's paths are the repository's; the blocks state their figures with
`assert`."""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

from conftest import ROOT

GUIDE = ROOT / "docs" / "guide" / "src"
BLOCK = re.compile(r"^```python[^\n]*\n(.*?)^```", re.MULTILINE | re.DOTALL)


def chapters_with_python() -> list[Path]:
    return [p for p in sorted(GUIDE.glob("*.md")) if BLOCK.search(p.read_text(encoding="utf-8"))]


def test_the_guide_has_python_blocks():
    assert chapters_with_python(), "no chapter of the guide holds a python block"


@pytest.mark.parametrize("chapter", chapters_with_python(), ids=lambda p: p.name)
def test_every_python_block_runs(chapter: Path, tmp_path: Path, monkeypatch):
    (tmp_path / "fixtures").symlink_to(ROOT / "fixtures")
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__guide__"}
    text = chapter.read_text(encoding="utf-8")
    for match in BLOCK.finditer(text):
        line = text.count("\n", 0, match.start()) + 2
        code = compile(match.group(1), f"{chapter.name}:{line}", "exec")
        exec(code, namespace)  # noqa: S102 - the guide's own examples
