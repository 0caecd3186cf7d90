"""Issue 39's teaching list: `tol` is worded one way, the CLI's `--tol` help, in every public
function that takes it (or the docstring points to the one that says it)."""
import inspect
import subprocess

import coatcontact as cc

WORDING = "relative tolerance of the solver's values, allowed 1e-13..1e-1 (default 1e-8)"


def public_callables_with_tol():
    for name in cc.__all__:
        obj = getattr(cc, name)
        members = [(name, obj)]
        if inspect.isclass(obj):
            members += [("%s.%s" % (name, m), f) for m, f in vars(obj).items()
                        if callable(f) and not m.startswith("_")]
            members.append((name, obj.__init__))
        for label, f in members:
            try:
                params = inspect.signature(f).parameters
            except (TypeError, ValueError):
                continue
            if "tol" in params:
                yield label, f, obj


def test_every_tol_is_worded_as_the_cli():
    found = 0
    for label, f, owner in public_callables_with_tol():
        found += 1
        doc = (f.__doc__ or "") + ((owner.__doc__ or "") if inspect.isclass(owner) else "")
        # kinetics_fit lists tol among the arguments "as kinetics()", which words it.
        assert WORDING in doc or "tol: as kinetics()" in doc, label
        assert inspect.signature(f).parameters["tol"].default == 1e-8, label
    assert found >= 9


def test_the_cli_words_it_so():
    from conftest import CLI
    out = subprocess.run([CLI, "reduced", "--help"], capture_output=True, text=True).stdout
    assert WORDING.replace("(default 1e-8)", "") in " ".join(out.split())
