import csv, sys, collections
REGS = {"operator_speech","first_person"}
for fname in sys.argv[1:]:
    rows = list(csv.DictReader(open("/work/main/data/writers/w16/"+fname, newline="", encoding="utf-8")))
    assert all(list(r.keys()) == ["id","writer","register","text","label","pair","type","setting","hazard"] for r in rows)
    ids = [r["id"] for r in rows]; assert len(ids) == len(set(ids)), "dup ids"
    texts = [r["text"] for r in rows]; assert len(texts) == len(set(texts)), "dup texts"
    assert all(r["label"] in ("0","1") for r in rows)
    assert all(r["register"] in REGS for r in rows)
    assert all(r["writer"] == "w16" and r["setting"] and r["hazard"] and " " not in r["setting"] for r in rows)
    pairs = collections.defaultdict(list)
    for r in rows:
        if r["pair"]:
            assert r["type"] == "minimal_pair"; pairs[r["pair"]].append(r)
        else:
            assert r["type"] == "single"
    for p, rs in pairs.items():
        assert len(rs) == 2, p
        assert {rs[0]["label"], rs[1]["label"]} == {"0","1"}, p
        assert rs[0]["register"] == rs[1]["register"], p
    c = collections.Counter((r["register"], r["label"]) for r in rows)
    print(fname, len(rows), "labels", collections.Counter(r["label"] for r in rows), "pairs", len(pairs), "paired rows", 2*len(pairs), dict(c))
