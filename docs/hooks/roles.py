"""MkDocs hook: a Sphinx role left in a docstring (``:func:`x```, ``:class:`x```, ...) is not
rendered by mkdocstrings, which reads docstrings as Markdown; the API reference would print
it raw. Each one found on a page is a warning, so ``mkdocs build --strict`` fails on it."""

from __future__ import annotations

import logging
import re

log = logging.getLogger("mkdocs.hooks.roles")

#: A role as mkdocstrings leaves it in the page: the role's name, a colon, then the code span.
RAW_ROLE = re.compile(r":(?:py:)?(?:mod|func|class|meth|attr|data|exc|obj|const|ref|math):"
                      r"(?:<code>|`)")


def on_page_content(html: str, page, config, files) -> str:  # noqa: ANN001
    for match in RAW_ROLE.finditer(html):
        start = max(match.start() - 40, 0)
        context = re.sub(r"<[^>]+>", "", html[start:match.end() + 40])
        log.warning("%s: a raw Sphinx role in a docstring: ...%s... (write it as a Markdown "
                    "code span)", page.file.src_uri, context.replace("\n", " "))
    return html
