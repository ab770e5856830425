import csv, sys, collections, re
path = sys.argv[1]
rows = list(csv.DictReader(open(path, encoding="utf-8")))
from common import COLS
TYPES = set('plain minimal_pair negation condition polite_harmful justified_harmful safe_mentions_danger multi_step first_person deception privacy property dignity jailbreak order_matters earlier_step_makes_safe context_decides'.split())
assert list(rows[0].keys()) == COLS, rows[0].keys()
ids = [r["id"] for r in rows]; assert len(ids) == len(set(ids)), "dup ids"
texts = [r["text"] for r in rows]
dups = [t for t, c in collections.Counter(texts).items() if c > 1]; assert not dups, dups[:1]
for r in rows:
    assert r["label"] in ("0","1"), r["id"]
    assert r["writer"] == "w09"
    assert r["register"] in ("scene_instruction","context_command"), r["id"]
    for k in ("type","setting","hazard"): assert r[k], (r["id"], k)
    assert r["type"] in TYPES, (r["id"], r["type"])
    assert r["id"].startswith("w09-"), r["id"]
    assert r["pair"] == "" or r["pair"].startswith("w09-p"), r["id"]
pairs = collections.defaultdict(list)
for r in rows:
    if r["pair"]: pairs[r["pair"]].append(r)
for p, rs in pairs.items():
    assert len(rs) == 2, p
    assert {x["label"] for x in rs} == {"0","1"}, p
    assert rs[0]["text"] != rs[1]["text"], p
print("rows", len(rows), "pairs", len(pairs), "paired frac %.2f" % (2*len(pairs)/len(rows)))
c = collections.Counter((r["register"], r["label"]) for r in rows); print(sorted(c.items()))
print("labels", collections.Counter(r["label"] for r in rows))
# scene word counts
wc = []
for r in rows:
    if r["register"] == "scene_instruction":
        scene = r["text"].split("\nTASK")[0]
        wc.append((len(scene.split()), r["id"]))
if wc:
    wc.sort(); print("scene words min", wc[:3], "max", wc[-2:])
print("types", collections.Counter(r["type"] for r in rows).most_common())
print("settings", collections.Counter(r["setting"] for r in rows).most_common())
