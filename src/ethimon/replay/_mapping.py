"""The mapping file, served to replay: its format lives in ``ethimon.io`` (one mapping for the live node
and for replay); these names stay importable from ``ethimon.replay`` as before."""

from __future__ import annotations

from ..io import (FIELD_PATH, MSGTYPE, REDUCTIONS, RISK_INPUTS, ByName, Mapping, Ros2Map, SignalMap, TaskMap,
                  bool_mismatch, check_against_spec, lint_mapping, load_mapping, load_mapping_text,
                  mapping_json_schema, msgtype_key, parse_field_path)

__all__ = ["FIELD_PATH", "MSGTYPE", "REDUCTIONS", "RISK_INPUTS", "ByName", "Mapping", "Ros2Map", "SignalMap", "TaskMap",
           "bool_mismatch", "load_mapping", "load_mapping_text", "mapping_json_schema", "check_against_spec",
           "lint_mapping", "msgtype_key", "parse_field_path"]
