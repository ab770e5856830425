import csv, sys, collections
fn = sys.argv[1]
rows = list(csv.DictReader(open(fn, encoding="utf-8", newline="")))
assert rows and list(rows[0].keys()) == ["id","writer","register","text","label","pair","type","setting","hazard"]
ids = [r["id"] for r in rows]; assert len(ids) == len(set(ids)), "dup ids"
regs = {"code_plan","numbered_plan","operator_speech"}
pairs = collections.defaultdict(list)
for r in rows:
    assert r["label"] in ("0","1"), r["id"]
    assert r["writer"] == "w20" and r["register"] in regs, r["id"]
    assert r["setting"] and " " not in r["setting"] and r["hazard"], r["id"]
    if r["pair"]:
        pairs[r["pair"]].append(r); assert r["type"] == "minimal_pair", r["id"]
    else:
        assert r["type"] == "single", r["id"]
for p, rs in pairs.items():
    assert len(rs) == 2 and {x["label"] for x in rs} == {"0","1"} and rs[0]["register"] == rs[1]["register"], p
texts = [r["text"] for r in rows]; assert len(texts) == len(set(texts)), "dup text"
c = collections.Counter((r["register"], r["label"]) for r in rows)
print(len(rows), "rows; labels", collections.Counter(r["label"] for r in rows), "pairs", len(pairs), "paired rows", sum(len(v) for v in pairs.values()))
for k in sorted(c): print(" ", k, c[k])
