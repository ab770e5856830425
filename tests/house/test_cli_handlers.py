"""The CLI is a thin layer (issue 33 item 5): every handler a parser dispatches to (``set_defaults(handler=...)``)
is at most 40 lines; it parses, calls the library (``ethimon.run`` for many files) and prints."""

from __future__ import annotations

import argparse
import inspect

from ethimon.cli import _build_parser

MAX_HANDLER_LINES = 40


def _handlers(p: argparse.ArgumentParser, seen: dict) -> dict:
    h = p.get_default("handler")
    if h is not None:
        seen[h.__qualname__] = h
    for a in p._actions:
        if isinstance(a, argparse._SubParsersAction):
            for child in a.choices.values():
                _handlers(child, seen)
    return seen


def test_every_cli_handler_is_short():
    handlers = _handlers(_build_parser(), {})
    assert len(handlers) >= 10
    long = {name: len(inspect.getsourcelines(fn)[0]) for name, fn in handlers.items()
            if len(inspect.getsourcelines(fn)[0]) > MAX_HANDLER_LINES}
    assert long == {}, f"CLI handlers over {MAX_HANDLER_LINES} lines (move the work into the library): {long}"
