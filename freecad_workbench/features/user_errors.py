"""User errors in a recompute: one clear line in the report view, no traceback.

A user error (ValueError: a deleted source face, a missing guide, a bad
parameter; or a cancelled run) must mark the object as failed, so FreeCAD's
tree and its recompute log show it, and that needs an exception out of
`execute`. FreeCAD 0.20 reports every exception out of a Python feature with
its Python traceback (`PyException::ThrowException` calls `ReportException`
before the recompute sees it), which tells a user nothing. So for user errors
the report view's and the console's error channel is closed from the raise
until the recompute is over (document observer, the next Qt event loop turn,
or the next Tessella execute, whichever comes first); our own line is printed
before. Errors of the code itself (anything else) keep their traceback: they
are bug reports.
"""

import functools

import FreeCAD

#: Console observers whose "Err" channel is closed while a traceback is due.
_OBSERVERS = ("ReportOutput", "Console")

_muted = {}  # observer -> its "Err" status before we closed it


def without_label(obj, exc):
    """The message of exc without a leading "<label>: " (the report line names
    the object once, not "Panelization: Panelization: ...")."""
    text = str(exc)
    prefix = f"{obj.Label}: "
    return text[len(prefix):] if text.startswith(prefix) else text


def is_user_error(exc):
    if isinstance(exc, ValueError):
        return True
    try:
        from ..core import Cancelled
    except ImportError:  # no compiled core: nothing was cancelled
        return False
    return isinstance(exc, Cancelled)


def _close_error_channel():
    for name in _OBSERVERS:
        if name in _muted:
            continue
        try:
            was = FreeCAD.Console.GetStatus(name, "Err")
        except Exception:  # observer not registered (headless)
            continue
        if was is None:
            continue
        _muted[name] = bool(was)
        FreeCAD.Console.SetStatus(name, "Err", False)
    _ensure_reopened_later()


def reopen_error_channel():
    """Restore the error channel closed for a user error's traceback (idempotent)."""
    while _muted:
        name, was = _muted.popitem()
        try:
            FreeCAD.Console.SetStatus(name, "Err", was)
        except Exception:
            pass


class _RecomputeObserver:
    """Reopens the channel when a recompute is over."""

    def slotRecomputedDocument(self, _doc):
        reopen_error_channel()


_observer = None


def _ensure_reopened_later():
    global _observer
    if _observer is None:
        _observer = _RecomputeObserver()
        FreeCAD.addDocumentObserver(_observer)
    if FreeCAD.GuiUp:
        from PySide import QtCore

        QtCore.QTimer.singleShot(0, reopen_error_channel)


def report(obj, exc):
    """Print the one report line for exc on obj; close the error channel for
    its traceback when it is a user error."""
    FreeCAD.Console.PrintError(f"Tessella: {obj.Label}: {without_label(obj, exc)}\n")
    if is_user_error(exc):
        _close_error_channel()


def reports_user_errors(execute):
    """Decorator of a proxy's execute(self, obj): see the module docstring."""

    @functools.wraps(execute)
    def wrapper(self, obj):
        reopen_error_channel()  # a previous object's error must not hide this one's
        try:
            return execute(self, obj)
        except Exception as exc:
            report(obj, exc)
            raise

    return wrapper
