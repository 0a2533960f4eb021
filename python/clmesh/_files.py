"""Triangle's files as input dictionaries: the triangle package's load() and
loads(), read by clmesh's own readers (those of the command line: the same
checks, errors naming the file and line).

They read .node, .poly, .ele and .area (not the outputs .edge and .neigh).
Indices come back zero-based whatever the files' numbering. A region line
reads as Triangle reads it: (x, y, attribute, maximum area), the attribute
standing for the maximum area when the line has no fifth value. A six-node
.ele gives its corners only.
"""

import os
import tempfile

from . import _clmesh
from ._errors import InputError

_EXTENSIONS = ("node", "poly", "ele", "area")


def _read(paths):
    return dict(_clmesh.read_files(*(paths.get(ext, "") for ext in _EXTENSIONS)))


def load(directory, name):
    """The input dict of the files directory/name.node, .poly, .ele and
    .area that exist (.poly's vertices first; .area with .ele only)."""
    paths = {}
    for ext in _EXTENSIONS:
        path = os.path.join(directory, f"{name}.{ext}")
        if os.path.exists(path):
            paths[ext] = path
    if not paths:
        raise InputError(f"{os.path.join(directory, name)}: no .node, .poly or .ele file")
    return _read(paths)


def loads(node=None, ele=None, poly=None, area=None, edge=None, neigh=None):
    """The input dict of Triangle files given as strings (edge and neigh are
    accepted and ignored). An error names the file by its kind
    ("<poly>:12: ...")."""
    texts = {"node": node, "poly": poly, "ele": ele, "area": area}
    with tempfile.TemporaryDirectory(prefix="clmesh-loads-") as folder:
        paths = {}
        for ext, text in texts.items():
            if text is not None:
                paths[ext] = os.path.join(folder, f"input.{ext}")
                with open(paths[ext], "w") as file:
                    file.write(text)
        if not paths:
            return {}
        try:
            return _read(paths)
        except InputError as error:
            message = str(error)
            for ext, path in paths.items():
                message = message.replace(path, f"<{ext}>")
            raise InputError(message) from None
