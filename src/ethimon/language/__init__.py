"""Stage 1 of 3: the spec language (YAML files, validated models, expressions)."""

from ..errors import ExprSyntaxError
from ._expr import parse_expr
from ._load import parse_spec_file, parse_spec_text
from ._operators import OPERATORS, Operator
from ._model import (DEFAULT_ALPHA, DEFAULT_BETA, DEFAULT_GAMMA, SEVERITY_ORDER, VARIANCE_MODES, Constant, Obligation,
                     OnFault, Release, Response, RiskConfig, RuleRelease, SafePose, Signal, Spec)
from ._time import seconds_to_cycles

__all__ = ["Constant", "Obligation", "Operator", "OPERATORS", "parse_expr", "parse_spec_file",
           "parse_spec_text", "Release", "Response", "SafePose", "Signal", "Spec"]
