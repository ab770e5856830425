import csv, os, sys
COLS = ["id","writer","register","text","label","pair","type","setting","hazard"]
def append(fname, rows):
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", fname)
    new = not os.path.exists(path)
    with open(path, "a", newline="", encoding="utf-8") as f:
        w = csv.writer(f, quoting=csv.QUOTE_MINIMAL, lineterminator="\n")
        if new:
            w.writerow(COLS)
        for r in rows:
            assert len(r) == 9, r
            w.writerow(r)
