import csv, os
HEADER = ["id","writer","register","text","label","pair","type","setting","hazard"]
def add(path, rows):
    new = not os.path.exists(path)
    with open(path, "a", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        if new:
            w.writerow(HEADER)
        for (rid, reg, text, label, pair, typ, setting, hazard) in rows:
            w.writerow([rid, "w06", reg, text, label, pair, typ, setting, hazard])
    print(path, "+", len(rows))
