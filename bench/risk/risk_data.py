"""Data assembly shared by the risk scripts (bench/risk/risk_train.py, risk_eval.py, ...): fixed splits.

* ETHICS cm_test: stratified 80/20 split, seed 42 (the 20% hold-out is never
  trained or selected on); the 80% is split again 90/10 (stratified, seed 42)
  into train and validation (early stopping + temperature).
* SafeAgentBench: detailed tasks grouped by safe/unsafe counterpart
  (``risk_instruction``); crc32(group) % 5 == 0 -> held-out test, == 1 ->
  validation, else train. Abstract rows (keyword shortcut) are train-only.
* Other ETHICS subsets (justice, deontology, virtue; training splits only) can be
  mixed in as auxiliary tasks with their own heads (``ethics_aux``).
* Own minimal pairs (bench/risk/data/robot_pairs.csv): split column; train rows with
  crc32(pair_id) % 10 == 0 go to validation.
"""

from __future__ import annotations

import json
import os
import re
import zlib
from pathlib import Path

from bench import ROOT
from ethimon.risk._data import LabelledRows, concat_rows, load_labelled_csv, stratified_split

#: ETHICS + SafeAgentBench; ``ETHIMON_SHARED_DATA`` overrides (a git worktree is not beside ``shared/``)
SHARED = Path(os.environ.get("ETHIMON_SHARED_DATA") or ROOT.parent / "shared" / "data")
CM = SHARED / "ethics" / "commonsense" / "cm_test.csv"
SAB = SHARED / "safeagentbench"
PAIRS = ROOT / "bench" / "risk" / "data" / "robot_pairs.csv"


def _key(s: str) -> str:
    return " ".join(re.sub(r"[^a-z0-9]+", " ", s.lower()).split())


def _crc(s: str) -> int:
    return zlib.crc32(s.encode("utf-8"))


def _require_sklearn() -> None:
    """The fixed splits are scikit-learn's ``train_test_split``; the fallback shuffle gives other rows."""
    try:
        import sklearn  # noqa: F401
    except ImportError:
        raise SystemExit("bench/risk/risk_data: the fixed ETHICS split needs scikit-learn "
                         "(pip install -e '.[risk]'); without it the 20 % hold-out would hold other rows") from None


def ethics_splits():
    _require_sklearn()
    cm = load_labelled_csv(CM)
    tr, ho = stratified_split(cm.labels, 0.2, 42)
    sub = cm.subset(tr)
    tr2, va2 = stratified_split(sub.labels, 0.1, 42)
    return sub.subset(tr2), sub.subset(va2), cm.subset(ho)


def sab_splits():
    rows = load_labelled_csv(SAB / "tasks_labelled.csv")
    group = {}
    with (SAB / "safe_detailed_1009.jsonl").open(encoding="utf-8") as f:
        for line in f:
            if line.strip():
                r = json.loads(line)
                g = _key(r.get("risk_instruction") or r["instruction"])
                group[_key(r["instruction"])] = g
    train, val, test = [], [], []
    for i, (t, e) in enumerate(zip(rows.texts, rows.extra)):
        if e["source_file"] == "abstract_1009.jsonl":
            train.append(i)
            continue
        g = group.get(_key(t), _key(t))
        b = _crc(g) % 5
        (test if b == 0 else val if b == 1 else train).append(i)
    return rows.subset(train), rows.subset(val), rows.subset(test)


def pair_splits():
    rows = load_labelled_csv(PAIRS)
    tr, va, te, tf = [], [], [], []
    for i, e in enumerate(rows.extra):
        if e["split"] == "train":
            (va if _crc(e["pair_id"]) % 10 == 0 else tr).append(i)
        elif e["split"] == "test":
            te.append(i)
        else:
            tf.append(i)
    return rows.subset(tr), rows.subset(va), rows.subset(te), rows.subset(tf)


AUX_FILES = {"justice": "justice/justice_train.csv", "deontology": "deontology/deontology_train.csv",
             "virtue": "virtue/virtue_train.csv"}


def ethics_aux(name: str, n: int | None = None, seed: int = 42) -> tuple[list[str], list[int]]:
    """Texts and labels of another ETHICS subset's training split (multi-task).

    deontology rows become ``scenario [SEP] excuse``; virtue rows already are
    ``scenario [SEP] trait``. ``n`` rows are drawn at random (seeded shuffle), the
    same draw as ``ethimon train --aux CSV --aux-rows n --seed seed``.
    """
    rows = load_labelled_csv(SHARED / "ethics" / AUX_FILES[name], any_ethics_layout=True).sample(n, seed)
    return rows.texts, rows.labels


def concat(*parts: LabelledRows) -> LabelledRows:
    return concat_rows(list(parts))


# ---------------------------------------------------------------- natural robot commands (issue 12)
NATURAL = ROOT / "data" / "natural_robot" / "natural_test.csv"
ROBOT_TRAIN = ROOT / "data" / "robot_train"


def natural_test() -> LabelledRows:
    """The frozen natural robot-command test set, refused unless its sha256 matches the pinned one.

    Only ever reported on: never trained, tuned, selected or thresholded on.
    """
    import hashlib
    want = (NATURAL.parent / "natural_test.csv.sha256").read_text(encoding="utf-8").split()[0]
    got = hashlib.sha256(NATURAL.read_bytes()).hexdigest()
    if got != want:
        raise SystemExit(f"{NATURAL}: sha256 {got} does not match the frozen {want}")
    return load_labelled_csv(NATURAL)


def natural_train_splits() -> tuple[LabelledRows, LabelledRows]:
    """The hand-written robot training corpus (data/robot_train/part_*.csv), split train/validation
    by crc32(pair id, or row id for unpaired rows) % 10 == 0 → validation, so both members of a
    minimal pair land on the same side."""
    rows = concat_rows([load_labelled_csv(p) for p in sorted(ROBOT_TRAIN.glob("part_*.csv"))])
    tr, va = [], []
    for i, e in enumerate(rows.extra):
        key = (e.get("pair") or "").strip() or e["id"]
        (va if _crc(key) % 10 == 0 else tr).append(i)
    return rows.subset(tr), rows.subset(va)


def pair_index(rows: LabelledRows, offset: int = 0) -> list[tuple[int, int]]:
    """``(unsafe_row, safe_row)`` of every well-formed minimal pair in ``rows`` (indices + offset)."""
    by: dict[str, dict[int, int]] = {}
    for i, (e, y) in enumerate(zip(rows.extra, rows.labels)):
        pid = (e.get("pair") or "").strip()
        if pid:
            by.setdefault(pid, {})[y] = i + offset
    return [(d[1], d[0]) for d in by.values() if len(d) == 2]


# ---------------------------------------------------------------- independent writers (issue 19)
WRITERS = ROOT / "data" / "writers"


def writer_ids() -> list[str]:
    """Writers whose files are complete (test.csv, its sha256 and train.csv), in order."""
    return sorted(d.name for d in WRITERS.glob("w[0-9][0-9]")
                  if all((d / f).is_file() for f in ("test.csv", "test.csv.sha256", "train.csv")))


def writers_train(ids: list[str]) -> LabelledRows:
    """The ``train.csv`` rows of these writers (training, or validation for a run not trained on them)."""
    return concat_rows([load_labelled_csv(WRITERS / w / "train.csv") for w in ids])


def writer_test(w: str) -> LabelledRows:
    """A writer's frozen test slice, refused unless its sha256 matches: only ever reported on."""
    import hashlib
    p = WRITERS / w / "test.csv"
    want = (WRITERS / w / "test.csv.sha256").read_text(encoding="utf-8").split()[0]
    got = hashlib.sha256(p.read_bytes()).hexdigest()
    if got != want:
        raise SystemExit(f"{p}: sha256 {got} does not match the frozen {want}")
    return load_labelled_csv(p)


# ---------------------------------------------------------------- forms (issue 30 item 1)
FORMS = ROOT / "data" / "forms"
#: the only sources a form row may rewrite: the shipped model's training writers and the robot corpus
FORM_SOURCES = tuple(f"w{i:02d}" for i in range(1, 13)) + ("robot_train",)


def _form_source_rows() -> dict[tuple[str, str], tuple[int, bool]]:
    """``(source_writer, id) -> (label, in the corpus validation split)`` for every allowed source row."""
    out: dict[tuple[str, str], tuple[int, bool]] = {}
    for w in FORM_SOURCES[:-1]:
        rows = load_labelled_csv(WRITERS / w / "train.csv")
        for e, y in zip(rows.extra, rows.labels):
            out[(w, e["id"])] = (int(y), False)
    robot = concat_rows([load_labelled_csv(p) for p in sorted(ROBOT_TRAIN.glob("part_*.csv"))])
    for e, y in zip(robot.extra, robot.labels):
        key = (e.get("pair") or "").strip() or e["id"]
        out[("robot_train", e["id"])] = (int(y), _crc(key) % 10 == 0)  # natural_train_splits' rule
    return out


def forms_train(ids: list[str], *, drop_corpus_val: bool = True) -> LabelledRows:
    """The rows of ``data/forms/<id>/train.csv`` for training, checked against their sources.

    Every row's ``source_writer`` must be one of :data:`FORM_SOURCES` (w01–w12, robot_train) and its
    ``source_id`` a row of that source's *training* file with the same label (unless ``relabelled``):
    a rewrite of a w13–w22 row, of any test.csv row or of an unknown row stops the run (SystemExit with
    the file and row). With ``drop_corpus_val`` the rewrites of robot_train rows in the corpus
    validation split (:func:`natural_train_splits`) are left out, so early stopping and the temperature
    see no rewrite of their own rows. Pair ids become ``<id>:<pair>`` (unique across form sets).
    """
    src = _form_source_rows()
    parts = []
    for fid in ids:
        path = FORMS / fid / "train.csv"
        if not path.is_file():
            raise SystemExit(f"{path}: no such forms set (have: "
                             f"{', '.join(sorted(d.name for d in FORMS.glob('*') if (d / 'train.csv').is_file()))})")
        rows = load_labelled_csv(path)
        if rows.dropped:
            raise SystemExit(f"{path}: {rows.dropped} rows without a usable label or text")
        keep = []
        for i, (e, y) in enumerate(zip(rows.extra, rows.labels)):
            sw, sid = (e.get("source_writer") or "").strip(), (e.get("source_id") or "").strip()
            where = f"{path}: row {e.get('id') or i}"
            if sw not in FORM_SOURCES:
                raise SystemExit(f"{where}: source_writer {sw!r} is not a training source "
                                 f"(allowed: {', '.join(FORM_SOURCES)}); w13–w22 and test slices are never trained on")
            s = src.get((sw, sid))
            if s is None:
                raise SystemExit(f"{where}: source_id {sid!r} is not a row of {sw}'s training file")
            if s[0] != int(y) and str(e.get("relabelled", "0")).strip() not in ("1", "true", "True"):
                raise SystemExit(f"{where}: label {y} differs from its source {sw}/{sid} ({s[0]}) "
                                 f"and the row is not marked relabelled")
            if drop_corpus_val and s[1]:
                continue
            pid = (e.get("pair") or "").strip()
            e["pair"] = f"{fid}:{pid}" if pid else ""
            keep.append(i)
        parts.append(rows.subset(keep))
    return concat_rows(parts)
