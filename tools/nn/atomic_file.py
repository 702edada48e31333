"""Outputs written under a temporary name and renamed when complete, as src/io/file_access.h's io::AtomicFile
does: an interrupted run never leaves a truncated file under the final name, and a failed rewrite keeps the
earlier file."""
import contextlib
import os


@contextlib.contextmanager
def atomic_path(path):
    """Yields a temporary path next to `path`, renamed onto `path` when the block completes, removed if it
    raises. The temporary name ends in `.partial`: writers that infer a format from the extension need it
    given (e.g. matplotlib's savefig(format="png"))."""
    directory, name = os.path.split(os.path.abspath(path))
    temporary = os.path.join(directory, f".{name}.{os.getpid()}.partial")
    try:
        yield temporary
        os.replace(temporary, path)
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)


@contextlib.contextmanager
def atomic_open(path, mode="w"):
    """open(path, mode) on a temporary file that replaces `path` when the block completes."""
    with atomic_path(path) as temporary:
        with open(temporary, mode) as f:
            yield f
