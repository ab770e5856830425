import csv, os, collections
COLS = ["id","writer","register","text","label","pair","type","setting","hazard"]
REG = {"context_command","operator_speech","numbered_plan"}
def append(path, rows):
    new = not os.path.exists(path)
    with open(path, "a", newline="", encoding="utf-8") as f:
        w = csv.writer(f, quoting=csv.QUOTE_MINIMAL, lineterminator="\n")
        if new: w.writerow(COLS)
        for r in rows:
            rid, reg, text, label, pair, typ, setting, hazard = r
            w.writerow([rid, "w21", reg, text, label, pair, typ, setting, hazard])
def check(path):
    rows = list(csv.DictReader(open(path, encoding="utf-8", newline="")))
    assert all(list(r.keys()) == COLS for r in rows)
    ids = [r["id"] for r in rows]; assert len(ids) == len(set(ids)), "dup id"
    assert all(r["label"] in ("0","1") for r in rows)
    assert all(r["register"] in REG for r in rows)
    texts = [r["text"] for r in rows]; assert len(texts) == len(set(texts)), "dup text"
    p = collections.defaultdict(list)
    for r in rows:
        if r["pair"]: p[r["pair"]].append(r)
        assert (r["type"] == "minimal_pair") == bool(r["pair"])
    for k, v in p.items():
        assert len(v) == 2, k
        assert {v[0]["label"], v[1]["label"]} == {"0","1"}, k
        assert v[0]["register"] == v[1]["register"], k
    c = collections.Counter((r["register"], r["label"]) for r in rows)
    print(path, len(rows), "pairs", len(p), dict(sorted(c.items())),
          "label1", sum(r["label"]=="1" for r in rows))

def append_train(rows, path="../train.csv"):
    # rows: (register, text, label, pair, type, setting, hazard); id assigned in order
    n = 0
    if os.path.exists(path):
        n = len(list(csv.DictReader(open(path, encoding="utf-8", newline=""))))
    out = []
    for i, r in enumerate(rows):
        out.append(("w21-%04d" % (n + i + 1),) + tuple(r))
    append(path, out)
    check(path)
