"""The report's look, shared by the stitched page (``index.html``) and each section page
opened on its own (``sections/NN_<name>.html``), and the rebasing of a page's relative
links when a section moves into another folder's page."""

from __future__ import annotations

import os
import re
from pathlib import Path

STYLE = """
body { font-family: sans-serif; margin: 0; color: #222; }
header, main, nav { box-sizing: border-box; }
header { max-width: 80em; margin: 0 auto; padding: 1em 1.5em 0; }
.layout { display: grid; grid-template-columns: 20em minmax(0, 1fr); gap: 2em;
          max-width: 100em; margin: 0 auto; padding: 0 1.5em; }
main.alone { max-width: 80em; margin: 0 auto; padding: 0 1.5em 2em; }
nav#contents { position: sticky; top: 0; align-self: start; max-height: 100vh;
               overflow-y: auto; font-size: 0.9em; padding: 1em 0; }
nav#contents ul { padding-left: 1.1em; margin: 0.2em 0; }
nav#contents li { margin: 0.15em 0; }
nav#contents details summary { cursor: pointer; color: #555; }
nav#contents .part { font-weight: bold; margin-top: 0.6em; }
nav#contents .part > ul { font-weight: normal; }
main { min-width: 0; }
table { border-collapse: collapse; font-size: 0.9em; }
th, td { padding: 0.2em 0.6em; border-bottom: 1px solid #ccc; text-align: right; }
th { white-space: nowrap; }
table.run th, table.run td, table.changes td { text-align: left; }
.table-scroll { overflow-x: auto; max-width: 100%; border-right: 1px solid #eee; }
td { min-width: 3em; }
figure { margin: 1.5em 0; min-width: 0; } figure img { max-width: 100%; }
figcaption { font-size: 0.9em; color: #333; margin-top: 0.4em; }
.figure-row { display: flex; flex-wrap: wrap; gap: 1.5em; align-items: flex-start; }
.figure-row figure { flex: 1 1 32em; margin: 1em 0; }
.note { background: #fff4d6; padding: 0.5em; border-left: 4px solid #e0a800; }
section { border-top: 2px solid #ddd; margin-top: 2em; }
h2.part { margin-top: 2em; color: #444; }
p.top { font-size: 0.85em; }
@media (max-width: 60em) { .layout { display: block; } nav#contents { position: static;
                                                                     max-height: none; } }
"""
"""CSS of every report page. Wide tables scroll inside their box (``.table-scroll``)
instead of spilling off the page: headers stay on one line and numbers and names never
break, so only text cells wrap to fit, and past that the box scrolls."""

#: ``src``/``href`` attributes in single quotes, as the toolkit writes them.
_LINK = re.compile(r"\b(src|href)='([^']*)'")


def rebase_links(text: str, source_dir: str | os.PathLike[str],
                 target_dir: str | os.PathLike[str]) -> str:
    """``text`` with every relative link (``src='...'``, ``href='...'``; not ``#anchor``,
    absolute paths or URLs with a scheme) moved from a page in ``source_dir`` to a page in
    ``target_dir``, so that it names the same file."""

    def moved(match: re.Match[str]) -> str:
        attribute, url = match.groups()
        if not url or url.startswith(("#", "/")) or re.match(r"^[A-Za-z][A-Za-z0-9+.-]*:", url):
            return match.group(0)
        path = os.path.relpath(Path(source_dir) / url, Path(target_dir))
        return f"{attribute}='{Path(path).as_posix()}'"

    return _LINK.sub(moved, text)
