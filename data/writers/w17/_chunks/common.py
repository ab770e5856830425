import csv, os, sys
from collections import Counter, defaultdict
COLS = ["id","writer","register","text","label","pair","type","setting","hazard"]
def append(path, rows):
    new = not os.path.exists(path)
    with open(path, "a", newline="", encoding="utf-8") as f:
        w = csv.writer(f, quoting=csv.QUOTE_MINIMAL, lineterminator="\n")
        if new:
            w.writerow(COLS)
        for r in rows:
            rid, text, label, pair, typ, setting, hazard = r
            w.writerow([rid, "w17", "context_command", text, label, pair, typ, setting, hazard])
def check(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    ids = [r["id"] for r in rows]
    assert len(ids) == len(set(ids)), "dup ids"
    pairs = defaultdict(list)
    for r in rows:
        assert list(r.keys()) == COLS
        assert r["label"] in ("0","1"), r["id"]
        assert r["register"] == "context_command"
        assert r["setting"] and " " not in r["setting"], r["id"]
        assert r["hazard"] and " " not in r["hazard"], r["id"]
        if r["pair"]:
            assert r["type"] == "minimal_pair", r["id"]
            pairs[r["pair"]].append(r)
        else:
            assert r["type"] == "single", r["id"]
    texts = [r["text"] for r in rows]
    assert len(texts) == len(set(texts)), "dup text"
    for p, rs in pairs.items():
        assert len(rs) == 2 and {x["label"] for x in rs} == {"0","1"}, p
    c = Counter(r["label"] for r in rows)
    paired = sum(len(v) for v in pairs.values())
    print(path, len(rows), dict(c), "pairs", len(pairs), "paired_frac", round(paired/len(rows),2))
    return rows
if __name__ == "__main__":
    check(sys.argv[1])
