"""House rules a newcomer relies on: no module of the three packages over 900 lines, no
private helper imported across modules (a leading underscore means "this module only")."""

import ast
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
PACKAGES = ("generators", "features", "cmtool")
MAX_LINES = 900
# kernel-internal names shared between the numba kernel modules on purpose (compile-time
# constants and inlined helpers cannot go through a public Python API)
KERNEL_MODULES = {"_kernels", "_integrators", "_lanes"}


def _modules():
    for package in PACKAGES:
        yield from sorted((REPO / package).rglob("*.py"))


def test_no_module_over_900_lines():
    long = {
        str(p.relative_to(REPO)): n
        for p in _modules()
        if (n := len(p.read_text().splitlines())) > MAX_LINES
    }
    assert not long, long


def test_no_private_name_imported_from_another_module():
    found = []
    for path in _modules():
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom) or node.module is None:
                continue
            source = node.module.rpartition(".")[2]
            if source in KERNEL_MODULES and path.stem in KERNEL_MODULES:
                continue
            for alias in node.names:
                if alias.name.startswith("_") and not alias.name.startswith("__"):
                    found.append(f"{path.relative_to(REPO)}: {node.module}.{alias.name}")
    assert not found, found
