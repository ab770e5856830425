import csv, os, sys
COLS = ["id","writer","register","text","label","pair","type","setting","hazard"]
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

def append(fname, rows):
    path = os.path.join(ROOT, fname)
    new = not os.path.exists(path)
    with open(path, "a", newline="", encoding="utf-8") as f:
        w = csv.writer(f, quoting=csv.QUOTE_MINIMAL, lineterminator="\n")
        if new:
            w.writerow(COLS)
        for r in rows:
            assert len(r) == 9, r
            w.writerow(r)
    print("appended", len(rows), "to", fname)
