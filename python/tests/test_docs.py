"""The Python parts of the documentation: the module's doctests, every ``python`` block of
README.md and the book run as shown, and the API reference (docs/src/reference/python.md)
is what the docstrings generate (``GONIOLIGHT_BLESS=1`` rewrites it; scripts/gen-docs.sh)."""

import doctest
import inspect
import os
import pathlib
import re

import pytest

import goniolight

ROOT = pathlib.Path(__file__).resolve().parents[2]
REFERENCE = ROOT / "docs" / "src" / "reference" / "python.md"


def documentation_files():
    files = [ROOT / "README.md"]
    files += sorted((ROOT / "docs" / "src").rglob("*.md"))
    return files


def python_blocks(path):
    """The ``python`` fenced blocks of a Markdown file: (line, code)."""
    text = path.read_text(encoding="utf-8")
    out = []
    for m in re.finditer(r"^```python\n(.*?)^```", text, flags=re.M | re.S):
        out.append((text[: m.start()].count("\n") + 1, m.group(1)))
    return out


@pytest.fixture
def example_folder(tmp_path, monkeypatch):
    """A folder with the bundled data linked in, as the examples' working directory."""
    for name in ("assets", "luminaires"):
        (tmp_path / name).symlink_to(ROOT / name)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_module_doctests_pass(example_folder):
    result = doctest.testmod(goniolight, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted >= 5
    assert result.failed == 0


EXAMPLES = [(p, line, code) for p in documentation_files() for line, code in python_blocks(p)]


def test_the_documentation_has_python_examples():
    assert len(EXAMPLES) >= 2


@pytest.mark.parametrize("path,line,code", EXAMPLES,
                         ids=[f"{p.relative_to(ROOT)}:{line}" for p, line, _ in EXAMPLES])
def test_python_example_runs(example_folder, path, line, code):
    exec(compile(code, f"{path.relative_to(ROOT)}:{line}", "exec"), {"__name__": "example"})


def _doc(obj):
    """A docstring as Markdown: ``code`` and :func:`name` as code spans, doctest sessions
    as ``pycon`` blocks (the doctest test runs them)."""
    text = inspect.getdoc(obj) or ""
    text = re.sub(r":\w+:`([^`]+)`", r"`\1`", text)
    text = re.sub(r"``([^`]+)``", r"`\1`", text)
    out, in_session = [], False
    for line in text.split("\n"):
        if line.startswith(">>>") and not in_session:
            out.append("```pycon")
            in_session = True
        elif in_session and not line.strip():
            out.append("```")
            in_session = False
        out.append(line)
    if in_session:
        out.append("```")
    return "\n".join(out)


def _entry(name, obj, level):
    heading = "#" * level
    if inspect.isclass(obj):
        out = [f"{heading} class `{name}`", "", _doc(obj), ""]
        for member, value in vars(obj).items():
            if member.startswith("_"):
                continue
            if isinstance(value, property):
                out += [f"{heading}# `{name}.{member}` (property)", "", _doc(value), ""]
            elif inspect.isfunction(value):
                out += _entry(f"{name}.{member}", value, level + 1)
        return out
    if callable(obj):
        signature = str(inspect.signature(obj)).replace("(self, ", "(").replace("(self)", "()")
        # Annotations are strings (`from __future__ import annotations`): unquote them.
        signature = re.sub(r"(: |-> )'([^']*)'", r"\1\2", signature)
        return [f"{heading} `{name}{signature}`", "", _doc(obj), ""]
    return [f"{heading} `{name}`", "", f"`{obj!r}`", ""]


def api_reference():
    """The Markdown page of the package's public API, from its docstrings."""
    out = ["# Python API", "",
           "<!-- Generated from the docstrings of python/goniolight/ by scripts/gen-docs.sh; "
           "edit them, not this page. -->", "",
           "```sh", "pip install ./python", "```", "", _doc(goniolight), ""]
    for name in goniolight.__all__:
        out += _entry(name, getattr(goniolight, name), 2)
    return "\n".join(out).rstrip() + "\n"


def test_api_reference_is_what_the_docstrings_generate():
    want = api_reference()
    if os.environ.get("GONIOLIGHT_BLESS"):
        REFERENCE.write_text(want, encoding="utf-8")
    have = REFERENCE.read_text(encoding="utf-8") if REFERENCE.exists() else ""
    assert have == want, "docs/src/reference/python.md is out of date: run scripts/gen-docs.sh"


def test_every_public_name_is_documented():
    for name in goniolight.__all__:
        obj = getattr(goniolight, name)
        if callable(obj):
            assert _doc(obj), f"goniolight.{name} has no docstring"


def test_the_native_stub_lists_what_the_module_exports():
    """``_native.pyi`` names every function and class of the extension and each method,
    and nothing it lacks (editors and type checkers read the stub)."""
    import ast
    import inspect

    from goniolight import _native

    stub = ast.parse((ROOT / "python" / "goniolight" / "_native.pyi").read_text())
    declared = {}
    for node in stub.body:
        if isinstance(node, ast.FunctionDef):
            declared[node.name] = None
        elif isinstance(node, ast.ClassDef):
            declared[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
    exported = {}
    for name, obj in vars(_native).items():
        if name.startswith("_"):
            continue
        if inspect.isclass(obj):
            exported[name] = {m for m in vars(obj) if not m.startswith("_")}
        elif callable(obj):
            exported[name] = None
    assert declared == exported
    assert (ROOT / "python" / "goniolight" / "py.typed").exists()
