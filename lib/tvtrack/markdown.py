"""The one Markdown escaper: generated text (register phrases, decisions, statements) made literal in Markdown,
so ``sigma*2`` stays ``sigma*2``, a ``|`` does not split a table cell and ``<b>`` is not HTML. Re-exported by
:mod:`tvtrack.results`; the report, the site, the register's table and the notebooks all use it."""

from __future__ import annotations

import re
from typing import Any

__all__ = ["md_escape"]

_MD_SPECIAL = re.compile(r"([\\`*_{}\[\]<>|~#])")


def md_escape(text: Any) -> str:
    """``text`` made literal in Markdown; line breaks become spaces."""
    return _MD_SPECIAL.sub(r"\\\1", " ".join(str(text).split()))
