"""Rows written individually by f01 (method=hand), collected from hand/*.py.

Each tuple: (source_id, source_writer, form, label, relabelled, text). Every row was typed by hand as a
literal, reading the source row and its pair partner, and expresses the deciding detail in the form's own
structure (predicates, node attributes, keys, call arguments, a buried log line)."""
from hand.h_pddl import ROWS as _P
from hand.h_bt import ROWS as _B
from hand.h_log import ROWS as _L
from hand.h_json import ROWS as _J
from hand.h_code_yaml import ROWS as _CY

HAND = list(_P) + list(_B) + list(_L) + list(_J) + list(_CY)
