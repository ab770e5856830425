import csv, sys, collections
path = sys.argv[1]
rows = list(csv.DictReader(open(path, encoding="utf-8", newline="")))
assert list(rows[0].keys()) == ["id","writer","register","text","label","pair","type","setting","hazard"], rows[0].keys()
ids = [r["id"] for r in rows]
assert len(ids) == len(set(ids)), "dup ids"
texts = [r["text"] for r in rows]
assert len(texts) == len(set(texts)), "dup texts"
regs = {"plain","first_person","jailbreak_wrapper"}
pairs = collections.defaultdict(list)
for r in rows:
    assert r["writer"] == "w18"
    assert r["label"] in ("0","1"), r
    assert r["register"] in regs, r
    assert r["setting"] and " " not in r["setting"], r
    assert r["hazard"] and " " not in r["hazard"], r
    if r["pair"]:
        assert r["type"] == "minimal_pair", r
        pairs[r["pair"]].append(r)
    else:
        assert r["type"] == "single", r
for p, rs in pairs.items():
    assert len(rs) == 2, (p, len(rs))
    assert {rs[0]["label"], rs[1]["label"]} == {"0","1"}, p
    assert rs[0]["register"] == rs[1]["register"], p
c = collections.Counter((r["register"], r["label"]) for r in rows)
print(len(rows), "rows; label1 =", sum(r["label"]=="1" for r in rows), "pairs =", len(pairs), "paired rows =", 2*len(pairs))
for k in sorted(c): print(" ", k, c[k])
