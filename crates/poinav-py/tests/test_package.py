"""The installed wheel: its version in step with the crates, one abi3 extension, the type
stubs, and the dependencies it declares (what `pip install` reads)."""

import importlib.metadata
import re
import sys
from pathlib import Path

import poinav
from conftest import REPO


def workspace_version():
    text = (REPO / "Cargo.toml").read_text()
    section = text[text.index("[workspace.package]"):]
    return re.search(r'^version = "([^"]+)"', section, re.M).group(1)


def test_version_in_step_with_the_crates():
    assert poinav.__version__ == workspace_version() == importlib.metadata.version("poinav")


def test_installed_wheel_not_the_source_tree():
    package = Path(poinav.__file__).resolve().parent
    # Installed into the test venv's site-packages, not imported from crates/poinav-py/python.
    assert "site-packages" in package.parts, package
    assert Path(sys.prefix).resolve() in package.parents
    natives = [p.name for p in package.iterdir() if p.name.startswith("_native.")]
    # One extension for every CPython >= 3.9 (the stable ABI), and its stubs.
    assert len([n for n in natives if n.endswith((".so", ".pyd"))]) == 1, natives
    assert any(".abi3." in n or n.endswith(".pyd") for n in natives), natives
    assert (package / "_native.pyi").is_file() and (package / "py.typed").is_file()
    files = {str(f) for f in importlib.metadata.files("poinav")}
    assert "poinav/dask.py" in files and "poinav/py.typed" in files


def test_declared_dependencies():
    meta = importlib.metadata.metadata("poinav")
    assert meta["Requires-Python"] == ">=3.9"
    requires = meta.get_all("Requires-Dist")
    assert any(re.match(r"numpy\s*>=\s*1\.21", r) for r in requires), requires
    assert set(meta.get_all("Provides-Extra")) == {"pandas", "dask"}

    def extra(name):
        return sorted(r.split(";")[0].strip() for r in requires
                      if r.split("extra ==")[-1].strip().strip("\"'") == name)

    assert extra("dask") == ["dask", "distributed", "pandas"]
    assert extra("pandas") == ["pandas"]
