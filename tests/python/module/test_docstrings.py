"""Every public name of the rotgen package has a reference entry (issue 47): a docstring of its
own, NumPy-style sections (napoleon reads them) where it takes parameters, returns a value or has
public attributes, each parameter and attribute named in its section."""

import ast
import inspect
import re
import textwrap

import pytest

import rotgen

HEADER = re.compile(r"^(?P<name>[A-Z][A-Za-z ]+)\n-{3,}$", re.M)


def sections(doc):
    """{section name: its text} of a NumPy-style docstring (after inspect.cleandoc)."""
    doc = inspect.cleandoc(doc)
    found = list(HEADER.finditer(doc))
    return {m.group("name"): doc[m.end():found[i + 1].start() if i + 1 < len(found) else None]
            for i, m in enumerate(found)}


def entry_names(section):
    """The names a Parameters or Attributes section documents: `name : type` or `name` lines at
    the section's indentation (`a, b : int` names two; `**keys` is `keys`)."""
    names = set()
    for line in section.splitlines():
        if not line.strip() or line.startswith((" ", "\t")):
            continue
        for name in line.split(" : ")[0].split(","):
            names.add(name.strip().lstrip("*"))
    return names


def own_doc(obj):
    """The object's own docstring (a class's, not one it inherits)."""
    doc = obj.__dict__.get("__doc__") if inspect.isclass(obj) else obj.__doc__
    return doc or ""


def public_classes():
    return [getattr(rotgen, n) for n in rotgen.__all__ if inspect.isclass(getattr(rotgen, n))]


def public_members():
    """(qualified name, object) of every public name: the package's __all__ (but __version__,
    a string) and the public methods and properties of its public classes."""
    out = []
    for name in rotgen.__all__:
        obj = getattr(rotgen, name)
        if isinstance(obj, str):
            continue
        out.append((name, obj))
        if inspect.isclass(obj):
            for member, value in vars(obj).items():
                if not member.startswith("_") and (inspect.isfunction(value)
                                                   or isinstance(value, property)):
                    out.append((f"{name}.{member}", value))
    return out


def parameters_of(obj):
    """The parameters a caller passes: a function's, or a class's constructor's (no self)."""
    target = obj.__init__ if inspect.isclass(obj) else obj
    if isinstance(obj, property) or (inspect.isclass(obj) and "__init__" not in vars(obj)):
        return []
    names = list(inspect.signature(target).parameters)
    return [n for n in names if n != "self"]


def returns_value(obj):
    """Whether a function's body returns a value (a `return EXPR` outside nested functions)."""
    if not inspect.isfunction(obj):
        return False
    tree = ast.parse(textwrap.dedent(inspect.getsource(obj)))
    function = tree.body[0]
    stack = list(function.body)
    while stack:
        node = stack.pop()
        if isinstance(node, ast.Return) and node.value is not None:
            return True
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            stack.extend(ast.iter_child_nodes(node))
    return False


def instance_attributes(cls):
    """The public attributes a class's methods set on self: `self.x = ...` (tuples too) and
    `setattr(self, key, ...)` in a loop over a tuple of names."""
    tree = ast.parse(textwrap.dedent(inspect.getsource(cls)))
    names = set()
    for node in ast.walk(tree):
        targets = node.targets if isinstance(node, ast.Assign) else []
        for target in targets:
            for t in (target.elts if isinstance(target, ast.Tuple) else [target]):
                if (isinstance(t, ast.Attribute) and isinstance(t.value, ast.Name)
                        and t.value.id == "self"):
                    names.add(t.attr)
        if isinstance(node, ast.For) and isinstance(node.iter, (ast.Tuple, ast.List)):
            setattrs = [c for c in ast.walk(node) if isinstance(c, ast.Call)
                        and isinstance(c.func, ast.Name) and c.func.id == "setattr"]
            if setattrs:
                names.update(e.value for e in node.iter.elts if isinstance(e, ast.Constant))
    return {n for n in names if not n.startswith("_")}


MEMBERS = public_members()


def test_the_public_names_are_the_documented_ones():
    # the module's own docstring introduces each public name (the API page's overview)
    names = {name for name in rotgen.__all__}
    assert names >= {"Model", "Scene", "simulate", "sweep", "emit", "InputError", "RunError",
                     "SimulateResult", "SweepResult", "__version__"}
    for name in names:
        assert name in rotgen.__doc__, f"rotgen's module docstring does not name {name}"
    # 12 names (fit and FitResult among them), 6 public methods: Model.equations, .inertia,
    # Scene.to_dict, .with_, SimulateResult.to_pandas, .events_to_pandas
    assert len(MEMBERS) == 17, [m for m, _ in MEMBERS]


@pytest.mark.parametrize("name,obj", MEMBERS, ids=[m for m, _ in MEMBERS])
def test_every_public_name_has_a_docstring_of_its_own(name, obj):
    doc = own_doc(obj).strip()
    assert doc, f"{name} has no docstring"
    summary = doc.splitlines()[0]
    assert len(summary.split()) >= 3, f"{name}: the first line is no summary: {summary!r}"


@pytest.mark.parametrize("name,obj", MEMBERS, ids=[m for m, _ in MEMBERS])
def test_parameters_are_documented_in_a_parameters_section(name, obj):
    wanted = parameters_of(obj)
    if not wanted:
        return
    found = sections(own_doc(obj))
    assert "Parameters" in found, f"{name} takes {wanted} but has no Parameters section"
    missing = set(wanted) - entry_names(found["Parameters"])
    assert not missing, f"{name}: Parameters does not document {sorted(missing)}"


@pytest.mark.parametrize("name,obj", MEMBERS, ids=[m for m, _ in MEMBERS])
def test_what_returns_a_value_has_a_returns_section(name, obj):
    if returns_value(obj):
        assert "Returns" in sections(own_doc(obj)), f"{name} returns a value: no Returns section"


@pytest.mark.parametrize("cls", public_classes(), ids=lambda c: c.__name__)
def test_public_attributes_are_documented_in_an_attributes_section(cls):
    attributes = instance_attributes(cls)
    assert attributes, f"{cls.__name__}: no attributes found (the source scan is broken)"
    found = sections(own_doc(cls))
    assert "Attributes" in found, f"{cls.__name__} has no Attributes section"
    missing = attributes - entry_names(found["Attributes"])
    assert not missing, f"{cls.__name__}: Attributes does not document {sorted(missing)}"


def test_the_checks_see_a_missing_entry():
    # the parsers above on a docstring with one parameter and one attribute left out
    doc = """Summary line here.

    Parameters
    ----------
    a : int
        First.

    Attributes
    ----------
    x, y : float
        Two.
    """
    found = sections(doc)
    assert entry_names(found["Parameters"]) == {"a"}
    assert entry_names(found["Attributes"]) == {"x", "y"}
    assert "Returns" not in found
