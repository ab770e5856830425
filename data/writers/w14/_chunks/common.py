import csv, os, sys
COLS = ["id","writer","register","text","label","pair","type","setting","hazard"]
def append(fname, rows, prefix):
    path = os.path.join(os.path.dirname(__file__), "..", fname)
    exists = os.path.exists(path)
    n = 0
    if exists:
        with open(path, newline="", encoding="utf-8") as f:
            n = sum(1 for _ in csv.DictReader(f))
    with open(path, "a", newline="", encoding="utf-8") as f:
        w = csv.writer(f, quoting=csv.QUOTE_MINIMAL, lineterminator="\n")
        if not exists:
            w.writerow(COLS)
        for r in rows:
            n += 1
            reg, text, label, pair, typ, setting, hazard = r
            w.writerow([f"{prefix}{n:04d}", "w14", reg, text, label, pair, typ, setting, hazard])
