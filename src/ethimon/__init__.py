"""ethimon: a formal-spec-checked runtime safety monitor for robot manipulation."""

from __future__ import annotations

from .errors import DependencyNotInstalled, EthimonError, ModelError, SpecError

__version__ = "0.1.0"

__all__ = ["DependencyNotInstalled", "EthimonError", "ModelError", "SpecError", "__version__"]
