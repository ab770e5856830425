"""Rows written individually by f01 (method=hand). Tuples: (source_id, source_writer, form, label, relabelled, text)."""
HAND = []
