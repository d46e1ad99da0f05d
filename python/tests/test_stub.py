# SPDX-License-Identifier: MIT
"""The type stub (calder/_calder.pyi) and the module name the same things,
so an editor completes and checks exactly the calls that exist."""

import ast
import pathlib

import calder
from calder import _calder

STUB = pathlib.Path(__file__).resolve().parents[1] / "calder" / "_calder.pyi"
HELPERS = {"VecLike", "FloatArray", "ArrayLike", "Field", "_Field", "_F"}  # typing only


def stub_tree():
    return ast.parse(STUB.read_text())


def members(node: ast.ClassDef):
    for item in node.body:
        if isinstance(item, ast.FunctionDef):
            yield item.name
        elif isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
            yield item.target.id
        elif isinstance(item, ast.Assign):
            yield from (t.id for t in item.targets if isinstance(t, ast.Name))


def test_every_stub_name_exists_in_the_module():
    for node in stub_tree().body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)) and node.name not in HELPERS:
            assert hasattr(_calder, node.name), node.name
            if isinstance(node, ast.ClassDef):
                cls = getattr(_calder, node.name)
                for name in members(node):
                    assert hasattr(cls, name), f"{node.name}.{name}"


def test_every_public_name_of_the_module_is_in_the_stub():
    declared = {node.name for node in stub_tree().body
                if isinstance(node, (ast.ClassDef, ast.FunctionDef))}
    public = {name for name in dir(_calder) if not name.startswith("_")}
    assert public - declared == set()


def test_every_public_method_of_a_stub_class_is_declared():
    for node in stub_tree().body:
        if not isinstance(node, ast.ClassDef) or node.name in HELPERS:
            continue
        declared = set(members(node))
        for base in node.bases:  # the fields' shared members
            if isinstance(base, ast.Name) and base.id == "_Field":
                declared |= {"enabled", "attached"}
        cls = getattr(_calder, node.name)
        if isinstance(cls, type) and issubclass(cls, BaseException):
            continue
        public = {n for n in vars(cls) if not n.startswith("_")}
        if hasattr(cls, "__members__"):  # enums: the values, and pybind11's name/value
            public -= {"name", "value"}
        assert public - declared == set(), node.name


def test_the_package_reexports_the_module():
    for name in dir(_calder):
        if not name.startswith("_"):
            assert getattr(calder, name) is getattr(_calder, name)


def test_every_field_class_declares_its_kinds_parameters():
    # The field classes are made from calder's descriptions of the kinds
    # (FieldKind<F>): the stub declares each parameter in the description's
    # order (then what the bindings add by hand, CustomForce's force), takes
    # each as a keyword, and its Field union holds every kind.
    tree = stub_tree()
    classes = {node.name: node for node in tree.body if isinstance(node, ast.ClassDef)}
    kinds = _calder._field_kinds()
    assert len(kinds) == len({cls for cls, *_ in kinds})
    for cls, name, keys, _in_scene_files in kinds:
        assert cls in classes, f"{cls} ({name}) is not in the stub"
        node = classes[cls]
        assert [b.id for b in node.bases if isinstance(b, ast.Name)] == ["_Field"], cls
        attributes = [item.target.id for item in node.body
                      if isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name)]
        assert attributes[:len(keys)] == list(keys), cls
        init = next(item for item in node.body
                    if isinstance(item, ast.FunctionDef) and item.name == "__init__")
        assert [a.arg for a in init.args.kwonlyargs] == attributes + ["enabled"], cls
    union = next(node.value for node in tree.body if isinstance(node, ast.Assign)
                 and any(isinstance(t, ast.Name) and t.id == "Field" for t in node.targets))
    assert [e.id for e in union.slice.elts] == [cls for cls, *_ in kinds]
