"""Deprecated: stage 1 is :mod:`ethimon.language` now (renamed in issue 24 so that it is not a ``spec``
folder beside ``specs/``); this module keeps ``ethimon.spec.<name>`` working for one release.

Importing it warns nothing; reading a name through it serves the same object from
:mod:`ethimon.language` (``load_spec``/``load_spec_text``: from :mod:`ethimon`) with a
:class:`DeprecationWarning`. Import from ``ethimon.language`` (or ``ethimon``) instead.

.. deprecated:: Unreleased
"""

from __future__ import annotations

import warnings

from . import language as _language

#: what ``from ethimon.spec import *`` saw: the language's public names
__all__ = list(_language.__all__)

#: names that were never ``ethimon.spec``'s own but that users reach for through it
_FROM_API = ("load_spec", "load_spec_text")


def __getattr__(name: str):
    if name in _language.__all__:
        value = getattr(_language, name)
    elif name in _FROM_API:
        from . import _api
        value = getattr(_api, name)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    warnings.warn(f"ethimon.spec is deprecated: import {name} from "
                  f"{'ethimon' if name in _FROM_API else 'ethimon.language'}", DeprecationWarning, stacklevel=2)
    return value


def __dir__() -> list[str]:
    return sorted(set(__all__) | set(_FROM_API))
