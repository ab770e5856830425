import csv, sys, collections
from common import COLS
f = sys.argv[1]
rows = list(csv.DictReader(open(f, newline="", encoding="utf-8")))
assert list(rows[0].keys()) == COLS
ids = [r["id"] for r in rows]; assert len(ids) == len(set(ids))
regs = {"code_plan","numbered_plan"}
pairs = collections.defaultdict(list)
for r in rows:
    assert r["label"] in ("0","1"), r["id"]
    assert r["register"] in regs, r["id"]
    assert r["writer"] == "w14"
    assert r["setting"] and r["hazard"]
    if r["pair"]:
        pairs[r["pair"]].append(r); assert r["type"] == "minimal_pair"
    else:
        assert r["type"] == "single"
for p, rs in pairs.items():
    assert len(rs) == 2, p
    assert {rs[0]["label"], rs[1]["label"]} == {"0","1"}, p
    assert rs[0]["register"] == rs[1]["register"], p
c = collections.Counter(r["label"] for r in rows)
texts = [r["text"] for r in rows]; assert len(texts) == len(set(texts)), "dup text"
print(len(rows), dict(c), "paired rows", sum(len(v) for v in pairs.values()),
      collections.Counter((r["register"], r["label"]) for r in rows))
