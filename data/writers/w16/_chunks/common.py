import csv, os
COLS = ["id","writer","register","text","label","pair","type","setting","hazard"]
BASE = "/work/main/data/writers/w16/"

def append(fname, prefix, rows):
    """rows: literal tuples (register, text, label, pair, type, setting, hazard)"""
    path = BASE + fname
    n = 0
    new = not os.path.exists(path)
    if not new:
        with open(path, newline="", encoding="utf-8") as f:
            n = sum(1 for _ in csv.DictReader(f))
    with open(path, "a", newline="", encoding="utf-8") as f:
        w = csv.writer(f, quoting=csv.QUOTE_MINIMAL, lineterminator="\n")
        if new:
            w.writerow(COLS)
        for r in rows:
            n += 1
            reg, text, label, pair, typ, setting, hazard = r
            w.writerow([f"{prefix}{n:04d}", "w16", reg, text, label, pair, typ, setting, hazard])
