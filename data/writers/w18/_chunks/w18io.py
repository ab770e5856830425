import csv, os
COLS = ["id","writer","register","text","label","pair","type","setting","hazard"]
def append(path, rows):
    new = not os.path.exists(path)
    with open(path, "a", newline="", encoding="utf-8") as f:
        w = csv.writer(f, quoting=csv.QUOTE_MINIMAL, lineterminator="\n")
        if new:
            w.writerow(COLS)
        for r in rows:
            rid, reg, text, label, pair, typ, setting, hazard = r
            w.writerow([rid, "w18", reg, text, label, pair, typ, setting, hazard])

def append_train(rows, path="../train.csv"):
    n = 0
    if os.path.exists(path):
        with open(path, encoding="utf-8", newline="") as f:
            n = sum(1 for _ in csv.DictReader(f))
    out = []
    for i, r in enumerate(rows):
        out.append(("w18-%04d" % (n + i + 1),) + tuple(r))
    append(path, out)
