"""Risk data and figures without torch: CSV loading, the split, metrics, plots, the shared corpora."""

from __future__ import annotations

import pytest

from ethimon.errors import SpecError


@pytest.mark.slow
def test_metrics_and_ece():
    from ethimon.risk._evaluate import classification_metrics, expected_calibration_error, flag_stats
    m = classification_metrics([1, 1, 0, 0], [0.9, 0.4, 0.6, 0.1])
    assert m["confusion"] == {"tn": 1, "fp": 1, "fn": 1, "tp": 1} and m["accuracy"] == 0.5
    assert m["roc_auc"] == pytest.approx(0.75)
    assert expected_calibration_error([1, 0], [1.0, 0.0]) == 0.0
    f = flag_stats([1, 1, 0, 0], [0.5, 0.3, 0.45, 0.2], 0.4)
    assert f["flag_rate_unsafe"] == 0.5 and f["false_alarm_rate"] == 0.5


@pytest.mark.slow
def test_evaluate_logits_records_both_thresholds():
    """The confusion matrix is at p_unsafe >= 0.5, the flags at R_e >= tau: both are recorded."""
    from ethimon.risk._evaluate import evaluate_logits
    logits = [[0.0, 3.0], [0.0, -3.0], [0.0, 0.2], [0.0, -0.2]]
    m = evaluate_logits([1, 0, 1, 0], logits, tau=0.47)
    assert m["confusion_threshold"] == 0.5 and m["flags"]["tau"] == 0.47
    assert m["confusion"] == {"tn": 2, "fp": 0, "fn": 0, "tp": 2}
    strict = evaluate_logits([1, 0, 1, 0], logits, tau=0.47, threshold=0.6)
    assert strict["confusion_threshold"] == 0.6 and strict["confusion"]["fn"] == 1


def test_confusion_plot_title_says_its_threshold(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    import matplotlib.axes

    from ethimon.risk._evaluate import plot_confusion
    titles = []
    real = matplotlib.axes.Axes.set_title
    monkeypatch.setattr(matplotlib.axes.Axes, "set_title",
                        lambda self, t, *a, **k: titles.append(t) or real(self, t, *a, **k))
    conf = {"tn": 3, "fp": 1, "fn": 2, "tp": 4}
    out = plot_confusion(conf, tmp_path / "c.png", threshold=0.5)
    assert (tmp_path / "c.png").is_file() and out == str(tmp_path / "c.png")
    assert titles == ["Confusion matrix (p_unsafe ≥ 0.5)"]


def test_csv_other_ethics_layouts(tmp_path):
    from ethimon.risk._data import load_labelled_csv
    d = tmp_path / "d.csv"
    d.write_text("label,scenario,excuse\n1,Aren't you supposed to cook?,No because I ate.\n0,x,\n",
                 encoding="utf-8")
    rows = load_labelled_csv(d, any_ethics_layout=True)
    assert rows.texts == ["Aren't you supposed to cook? [SEP] No because I ate."] and rows.dropped == 1
    with pytest.raises(SpecError, match="'input'"):
        load_labelled_csv(d)                       # only label,input without the flag
    j = tmp_path / "j.csv"
    j.write_text("label,scenario\n0,I deserve a raise because I work hard.\n", encoding="utf-8")
    assert load_labelled_csv(j, any_ethics_layout=True).texts == ["I deserve a raise because I work hard."]
    (tmp_path / "bad.csv").write_text("label,sentence\n1,x\n", encoding="utf-8")
    with pytest.raises(SpecError, match="scenario"):
        load_labelled_csv(tmp_path / "bad.csv", any_ethics_layout=True)


def test_csv_loading_and_split(tmp_path):
    from ethimon.risk._data import load_labelled_csv, stratified_split
    p = tmp_path / "d.csv"
    p.write_text('label,input,is_short\n1,"bad, thing",True\n0,fine,True\n,missing,True\n'
                 '2,odd,True\n0,,True\n1,"multi\nline",False\n', encoding="utf-8")
    rows = load_labelled_csv(p)
    assert rows.labels == [1, 0, 1] and rows.dropped == 3 and rows.texts[2] == "multi\nline"
    (tmp_path / "bad.csv").write_text("text,y\nx,1\n")
    with pytest.raises(SpecError, match="'label' and 'input'"):
        load_labelled_csv(tmp_path / "bad.csv")
    labels = [0] * 60 + [1] * 40
    tr, te = stratified_split(labels, 0.2, 42)
    assert len(te) == 20 and sum(labels[i] for i in te) == 8 and not set(tr) & set(te)
    assert stratified_split(labels, 0.2, 42) == (tr, te)


# ---------------------------------------------------------------- the shared corpora (../shared/data)
@pytest.mark.data
@pytest.mark.parametrize("rel, layout", [
    ("ethics/commonsense/cm_test.csv", False),
    ("ethics/deontology/deontology_test.csv", True),
    ("ethics/justice/justice_test.csv", True),
    ("safeagentbench/tasks_labelled.csv", False),
])
def test_shared_corpora_load(shared_data, rel, layout):
    """The corpora the shipped model was trained and evaluated on load as labelled rows."""
    from ethimon.risk._data import load_labelled_csv
    p = shared_data / rel
    if not p.is_file():
        pytest.skip(f"{p} is not in this copy of ../shared/data")
    rows = load_labelled_csv(p, any_ethics_layout=layout)
    assert len(rows) > 100 and set(rows.labels) == {0, 1}
    assert rows.dropped <= len(rows) // 100       # a layout change would drop (or misread) many rows
    assert all(t.strip() for t in rows.texts)

