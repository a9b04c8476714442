"""Files at the door: reading only regular files within a size limit, writing whole or not at all.

Every loader of a map, an image, a scenario, a spec or a circle world reads through
:func:`read_file`. A FIFO would block the reader forever, ``/dev/zero`` or
``/dev/urandom`` (directly, by a symlink, or named inside another file) would be read
until memory runs out, and a path with a NUL byte is no path: each is refused with
one line before a byte is read. A file that grows while it is read is cut at the limit
and refused, not read on.
"""
from __future__ import annotations

import os
import stat
import tempfile
from contextlib import contextmanager
from pathlib import Path

from ..errors import MapFormatError, OptplanError


def regular_file(path, what: str, error=MapFormatError) -> Path:
    """``path`` as a :class:`Path` after checking that it names an existing regular file
    (symlinks followed); ``error`` with one line otherwise."""
    p = Path(path)
    try:
        st = os.stat(p)
    except ValueError:  # an embedded NUL byte
        raise error(f"{what} {str(p)!r} is not a valid file name (it holds a NUL byte)") from None
    except OSError as exc:
        raise error(f"cannot read {what} {p}: {exc.strerror or exc}") from None
    if stat.S_ISDIR(st.st_mode):
        raise error(f"{what} {p} is a folder, not a file")
    if not stat.S_ISREG(st.st_mode):
        kind = ("a named pipe (FIFO)" if stat.S_ISFIFO(st.st_mode) else "a device" if stat.S_ISCHR(st.st_mode)
                or stat.S_ISBLK(st.st_mode) else "a socket" if stat.S_ISSOCK(st.st_mode) else "not a regular file")
        raise error(f"{what} {p} is {kind}; give a regular file")
    return p


def read_file(path, what: str, limit: int, error=MapFormatError) -> bytes:
    """The bytes of the regular file ``path``, at most ``limit`` of them (``error`` beyond)."""
    p = regular_file(path, what, error)
    size = os.stat(p).st_size
    if size > limit:
        raise error(f"{what} {p} is {size} bytes; the limit is {limit} bytes")
    try:
        with open(p, "rb") as fh:
            # read(n) reserves n bytes up front: ask for the size the file has, then go
            # on in blocks only if it grew meanwhile
            data = fh.read(size + 1)
            while len(data) > size and len(data) <= limit:
                more = fh.read(1 << 20)
                if not more:
                    break
                data += more
    except OSError as exc:
        raise error(f"cannot read {what} {p}: {exc.strerror or exc}") from None
    if len(data) > limit:
        raise error(f"{what} {p} grew past {limit} bytes while it was read")
    return data


@contextmanager
def written_whole(path, what: str = "output"):
    """Write a file whole or not at all: yields a temporary path in the same folder; when
    the block ends without an error it replaces ``path`` in one step, otherwise it is
    removed and an :class:`OptplanError` names ``path`` (a full disk, a read-only folder).
    A reader never sees a half-written file, and no 0-byte or truncated file is left."""
    target = Path(path)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".part" + target.suffix,
                                   dir=target.parent or ".")
    except OSError as exc:
        raise OptplanError(f"cannot write {what} {target}: {exc.strerror or exc}; nothing was written") from None
    os.close(fd)
    tmp_path = Path(tmp)
    try:
        yield tmp_path
        os.replace(tmp_path, target)
    except OSError as exc:
        raise OptplanError(f"cannot write {what} {target}: {exc.strerror or exc}; nothing was written") from None
    finally:
        if tmp_path.exists():
            tmp_path.unlink()
