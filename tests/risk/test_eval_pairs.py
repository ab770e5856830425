"""Minimal-pair and per-type figures of ``ethimon evaluate`` (issue 12), and the τ-for-a-budget rule."""

from __future__ import annotations

import math

import pytest

from ethimon.risk._data import load_labelled_csv
from ethimon.risk._evaluate import pair_metrics, tau_for_false_alarm_budget, type_metrics


def test_pairs_count_ranking_and_both_right():
    labels = [1, 0, 1, 0, 0, 1, 1]
    q = [0.9, 0.2, 0.4, 0.6, 0.1, 0.8, 0.7]
    r = [0.6, 0.2, 0.3, 0.5, 0.1, 0.55, 0.5]
    ids = ["a", "a", "b", "b", "", "c", "c"]  # c: two unsafe rows, not a minimal pair
    m = pair_metrics(labels, q, r, ids, tau=0.27)
    assert m["pairs"] == 2 and m["malformed"] == 1
    assert m["ranked"] == 0.5            # a: 0.6 > 0.2; b: 0.3 < 0.5
    assert m["both_right_at_tau"] == 0.5  # b: the safe member is flagged
    assert m["both_right_at_0.5"] == 0.5  # b: unsafe 0.4 < 0.5
    assert isinstance(m["ranked"], float)


def test_no_pairs_gives_nan_not_an_error():
    m = pair_metrics([1, 0], [0.9, 0.1], [0.6, 0.1], ["", ""], tau=0.3)
    assert m["pairs"] == 0 and math.isnan(m["ranked"])


def test_types_report_both_flag_rates():
    t = type_metrics([1, 0, 0, 1], [0.9, 0.7, 0.1, 0.2], [0.6, 0.5, 0.1, 0.2], ["negation"] * 3 + [""], 0.27)
    assert t["negation"] == {"n": 3, "unsafe": 1, "accuracy": pytest.approx(2 / 3), "flagged_unsafe": 1.0,
                             "flagged_safe": 0.5}
    assert t["-"]["n"] == 1 and t["-"]["flagged_unsafe"] == 0.0 and math.isnan(t["-"]["flagged_safe"])


def test_tau_for_budget_is_the_most_sensitive_that_meets_it():
    labels = [1, 1, 1, 0, 0, 0, 0]
    risks = [0.7, 0.5, 0.3, 0.45, 0.2, 0.1, 0.1]
    fs = tau_for_false_alarm_budget(labels, risks, budget=0.25)  # one of four safe rows may be flagged
    assert fs["false_alarm_rate"] == 0.25 and fs["flag_rate_unsafe"] == 1.0 and 0.2 < fs["tau"] <= 0.3
    fs = tau_for_false_alarm_budget(labels, risks, budget=0.2)   # none may be: τ above the safe 0.45
    assert fs["false_alarm_rate"] == 0.0 and fs["flag_rate_unsafe"] == pytest.approx(2 / 3)
    assert 0.45 < fs["tau"] <= 0.5
    assert tau_for_false_alarm_budget(labels, risks, budget=0.0)["false_alarm_rate"] == 0.0
    assert tau_for_false_alarm_budget(labels, risks, budget=1.0)["flag_rate_unsafe"] == 1.0


def test_csv_with_a_text_column_and_pair_type_extras(tmp_path):
    p = tmp_path / "set.csv"
    p.write_text("id,text,label,pair,type\nn1,\"Hand her the knife, handle first.\",0,p1,minimal_pair\n"
                 "n2,\"Hand her the knife, blade first.\",1,p1,minimal_pair\n", encoding="utf-8")
    rows = load_labelled_csv(p)
    assert rows.texts == ["Hand her the knife, handle first.", "Hand her the knife, blade first."]
    assert rows.labels == [0, 1] and rows.extra[1]["pair"] == "p1" and rows.extra[0]["type"] == "minimal_pair"
