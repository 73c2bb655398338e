"""The type hints (shapegen.pyi) describe the module as it is."""

import ast
import pathlib

import shapegen

STUB = pathlib.Path(__file__).resolve().parents[1] / "shapegen.pyi"


def stub():
    tree = ast.parse(STUB.read_text())
    names, classes = set(), {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            names.add(node.name)
        elif isinstance(node, ast.ClassDef):
            names.add(node.name)
            classes[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
    return names, classes


def test_every_public_name_is_in_the_stub_and_the_module():
    names, classes = stub()
    # maturin's package holds the native module as `shapegen.shapegen`.
    public = {n for n in dir(shapegen) if not n.startswith("_")} - {"shapegen"} | {"__version__"}
    assert names - {"ArrayLike", "Settings"} == public
    for name, members in classes.items():
        cls = getattr(shapegen, name)
        ours = {m for m in vars(cls) if not m.startswith("_") or m in {"__len__", "__eq__", "__hash__"}}
        if issubclass(cls, Exception):
            continue
        assert members == ours, name


def test_every_function_and_method_has_a_docstring():
    for name in dir(shapegen):
        value = getattr(shapegen, name)
        if name.startswith("_") or not callable(value):
            continue
        assert value.__doc__, name
        for member, attr in vars(value).items() if isinstance(value, type) else []:
            if not member.startswith("_"):
                assert attr.__doc__, f"{name}.{member}"
