"""bench/risk/risk_data.forms_train: form rows train only on allowed sources (fast, no model, tiny CSVs)."""

from __future__ import annotations

import pytest

HEAD = "id,writer,source_id,source_writer,form,method,text,label,pair,type,setting,hazard,relabelled\n"


def _tree(tmp_path, monkeypatch, form_rows: str):
    from bench.risk import risk_data as D
    w = tmp_path / "writers"
    for i in range(1, 13):
        d = w / f"w{i:02d}"
        d.mkdir(parents=True)
        (d / "train.csv").write_text("id,text,label,pair\n"
                                     f"w{i:02d}-0001,cut it,1,p{i}\nw{i:02d}-0002,do not cut it,0,p{i}\n")
    rt = tmp_path / "robot_train"
    rt.mkdir()
    (rt / "part_a.csv").write_text("id,text,label,pair\n" + "".join(
        f"r{k:03d},text {k},{k % 2},\n" for k in range(40)))
    f = tmp_path / "forms" / "fx"
    f.mkdir(parents=True)
    (f / "train.csv").write_text(HEAD + form_rows)
    monkeypatch.setattr(D, "WRITERS", w)
    monkeypatch.setattr(D, "ROBOT_TRAIN", rt)
    monkeypatch.setattr(D, "FORMS", tmp_path / "forms")
    return D


def test_forms_keep_allowed_rows_and_prefix_pairs(tmp_path, monkeypatch):
    from bench.risk import risk_data as D
    val = [k for k in range(40) if D._crc(f"r{k:03d}") % 10 == 0]
    trn = [k for k in range(40) if D._crc(f"r{k:03d}") % 10 != 0]
    assert val and trn
    rows = (f"x1,fx,w03-0001,w03,sms,template,pls cut it,1,q1,,,,0\n"
            f"x2,fx,w03-0002,w03,sms,template,pls dont cut it,0,q1,,,,0\n"
            f"x3,fx,r{trn[0]:03d},robot_train,chat,template,hi: text,{trn[0] % 2},,,,,0\n"
            f"x4,fx,r{val[0]:03d},robot_train,chat,template,hi: val,{val[0] % 2},,,,,0\n")
    D = _tree(tmp_path, monkeypatch, rows)
    got = D.forms_train(["fx"])
    assert [e["id"] for e in got.extra] == ["x1", "x2", "x3"]          # the corpus-validation rewrite is left out
    assert [e["pair"] for e in got.extra] == ["fx:q1", "fx:q1", ""]
    assert D.pair_index(got) == [(0, 1)]
    assert len(D.forms_train(["fx"], drop_corpus_val=False)) == 4


@pytest.mark.parametrize("row, msg", [
    ("x1,fx,w13-0001,w13,sms,template,cut,1,,,,,0\n", "not a training source"),
    ("x1,fx,w03-t0001,w03,sms,template,cut,1,,,,,0\n", "is not a row of w03's training file"),
    ("x1,fx,w03-0001,w03,sms,template,cut,0,,,,,0\n", "not marked relabelled"),
])
def test_forms_refuse_other_sources(tmp_path, monkeypatch, row, msg):
    D = _tree(tmp_path, monkeypatch, row)
    with pytest.raises(SystemExit, match=msg):
        D.forms_train(["fx"])
