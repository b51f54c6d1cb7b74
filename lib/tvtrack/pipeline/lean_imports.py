"""papermill and nbformat, imported without the cost nbformat never uses.

Both import ``jsonschema``, whose format checkers import ``rfc3987_syntax`` where it is installed (a dependency of
``jupyter-events``, so always here): that package builds 38 ``lark`` parsers when imported, about 1 s of CPU in
every process that runs or reads a notebook (each ``tvtrack run``, each sweep worker, the site build): most of a
small run's own cost. Its only use is the ``iri`` format check of JSON Schema drafts 7 and later; nbformat
validates notebooks against a draft-4 schema without a format checker, so nothing it checks changes. The package
is kept out only while ``jsonschema`` is first imported, and importable again afterwards.
"""

from __future__ import annotations

import sys
from contextlib import contextmanager
from types import ModuleType

__all__ = ["papermill", "nbformat"]

_SKIPPED = "rfc3987_syntax"


@contextmanager
def _without_iri_syntax():
    """While jsonschema is first imported, ``import rfc3987_syntax`` raises ImportError (jsonschema then leaves
    out the ``iri`` format check); nothing changes when jsonschema is already imported."""
    if "jsonschema" in sys.modules or _SKIPPED in sys.modules:
        yield
        return
    sys.modules[_SKIPPED] = None  # type: ignore[assignment]  # the import system's "not importable"
    try:
        yield
    finally:
        if _SKIPPED in sys.modules and sys.modules[_SKIPPED] is None:
            del sys.modules[_SKIPPED]


def papermill() -> ModuleType:
    """The ``papermill`` module (imported on first call)."""
    with _without_iri_syntax():
        import papermill as pm
    return pm


def nbformat() -> ModuleType:
    """The ``nbformat`` module (imported on first call)."""
    with _without_iri_syntax():
        import nbformat as nbf
    return nbf
