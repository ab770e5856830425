import csv, sys, os, collections
from common import ROOT, COLS
REG = {"plain","numbered_plan","code_plan","operator_speech","first_person","context_command","scene_instruction","jailbreak_wrapper"}
fname = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(ROOT, fname), encoding="utf-8", newline="")))
hdr = open(os.path.join(ROOT, fname), encoding="utf-8").readline().strip().split(",")
assert hdr == COLS, hdr
ids = [r["id"] for r in rows]; assert len(ids) == len(set(ids)), "dup ids"
pairs = collections.defaultdict(list)
texts = set()
for r in rows:
    assert r["writer"] == "w15"
    assert r["register"] in REG, r["id"]
    assert r["label"] in ("0","1"), r["id"]
    assert r["text"] not in texts, ("dup text", r["id"]); texts.add(r["text"])
    assert r["setting"] and " " not in r["setting"], r["id"]
    assert r["hazard"] and " " not in r["hazard"], r["id"]
    if r["pair"]:
        assert r["type"] == "minimal_pair", r["id"]
        pairs[r["pair"]].append(r)
    else:
        assert r["type"] != "minimal_pair", r["id"]
for p, rs in pairs.items():
    assert len(rs) == 2, (p, len(rs))
    assert {rs[0]["label"], rs[1]["label"]} == {"0","1"}, p
    assert rs[0]["register"] == rs[1]["register"], p
c = collections.Counter(r["label"] for r in rows)
reg = collections.Counter((r["register"], r["label"]) for r in rows)
paired = sum(len(v) for v in pairs.values())
print(fname, "rows", len(rows), "labels", dict(c), "pairs", len(pairs), "paired rows %.0f%%" % (100*paired/max(1,len(rows))))
print(sorted(reg.items()))
print("settings", collections.Counter(r["setting"] for r in rows).most_common())
