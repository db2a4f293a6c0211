"""The image folders a test sheet names, checked before any job runs.

A test whose row gives an ``images`` folder (:mod:`contactlab.testsheet`) needs, before its
correlation can run: the sidecar ``contactlab.json`` with valid keys
(:func:`contactlab.dic.sidecar.read_sidecar`), frames of one size and bit depth with
distinct ids (:class:`contactlab.dic.images.ImageFolder`, from the files' headers) and an
image for every frame of its load log. :func:`check_image_folders` checks them and raises
one line naming the sheet, line, test and column, then the file and what is wrong.
Folders and load logs a workflow rule writes (the demo) are checked by the job instead.
"""

from __future__ import annotations

from collections.abc import Collection
from pathlib import Path

import pandas as pd

from contactlab.testsheet import TestSheetError

__all__ = ["check_image_folders", "image_folder"]


def image_folder(folder: str | Path, *, colour: str, load_log: str | Path | None = None
                 ) -> list[int]:
    """Check an image folder (and that it holds every frame of ``load_log``, if given);
    return its frame ids. Raises ValueError or FileNotFoundError naming the file."""
    from contactlab.dic.images import ImageFolder
    from contactlab.dic.sidecar import read_sidecar

    setup = read_sidecar(folder)
    images = ImageFolder(setup.folder, reference=setup.reference, colour=colour)
    if load_log is not None:
        from contactlab.stiffness.readers import read_load_log

        images.require(read_load_log(load_log)["frame"].tolist())
    return list(images.frames)


def check_image_folders(sheet: pd.DataFrame, sheet_path: str | Path, *, colour: str,
                        root: str | Path = ".", generated: Collection[str] = ()) -> None:
    """Raise :class:`TestSheetError` for the first test (in sheet order) whose image folder
    fails :func:`image_folder`; folders (and load logs) in ``generated`` are skipped (not
    checked against)."""
    made = {Path(p).as_posix() for p in generated}
    lines = sheet.attrs.get("line", {})
    for test_id, row in sheet.iterrows():
        value = row.get("images")
        if value is None or pd.isna(value) or not str(value).strip():
            continue
        folder = str(value).strip()
        if Path(folder).as_posix() in made:
            continue
        log = row.get("load_log")
        log = None if log is None or pd.isna(log) or not str(log).strip() else str(log).strip()
        if log is not None and Path(log).as_posix() in made:
            log = None
        try:
            image_folder(Path(root) / folder, colour=colour,
                         load_log=None if log is None else Path(root) / log)
        except (ValueError, FileNotFoundError) as exc:
            raise TestSheetError(f"{sheet_path}: line {lines.get(test_id, '?')} (test "
                                 f"{test_id}), column 'images': {exc}") from None
