import csv, sys, collections
path = sys.argv[1]
COLS = ["id","writer","register","text","label","pair","type","setting","hazard"]
with open(path, newline="", encoding="utf-8") as f:
    rd = csv.reader(f)
    hdr = next(rd)
    assert hdr == COLS, hdr
    rows = [dict(zip(COLS, r)) for r in rd]
ids = [r["id"] for r in rows]
assert len(ids) == len(set(ids)), "dup ids"
bad = []
pairs = collections.defaultdict(list)
texts = collections.Counter(r["text"] for r in rows)
assert max(texts.values()) == 1, "dup text"
for r in rows:
    assert r["writer"] == "w13"
    assert r["label"] in ("0","1"), r["id"]
    assert r["register"] in ("scene_instruction","context_command"), r["id"]
    assert r["type"] in ("minimal_pair","single"), r["id"]
    assert (r["type"]=="minimal_pair") == bool(r["pair"]), r["id"]
    assert r["setting"] and " " not in r["setting"] and r["hazard"] and " " not in r["hazard"], r["id"]
    if r["pair"]: pairs[r["pair"]].append(r)
    t = r["text"]
    if r["register"] == "scene_instruction":
        assert t.count("\nInstruction: ") == 1, r["id"]
        scene = t.split("\nInstruction: ")[0]
        n = len(scene.split())
        if not (80 <= n <= 250): bad.append((r["id"], n))
    else:
        assert "Instruction:" not in t and "\n" in t, r["id"]
for p, rs in pairs.items():
    assert len(rs) == 2, p
    assert {rs[0]["label"], rs[1]["label"]} == {"0","1"}, p
    assert rs[0]["register"] == rs[1]["register"], p
print("rows", len(rows), "labels", collections.Counter(r["label"] for r in rows))
print("registers", collections.Counter((r["register"], r["label"]) for r in rows))
print("pairs", len(pairs), "paired rows", sum(len(v) for v in pairs.values()))
print("settings", collections.Counter(r["setting"] for r in rows))
print("short/long scenes", bad)
