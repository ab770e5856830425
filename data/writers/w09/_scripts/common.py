import csv, os
COLS = ["id","writer","register","text","label","pair","type","setting","hazard"]
def append(path, rows):
    new = not os.path.exists(path)
    with open(path, "a", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        if new:
            w.writerow(COLS)
        for r in rows:
            rid, reg, text, label, pair, typ, setting, hazard = r
            w.writerow([rid, "w09", reg, text.strip("\n"), label, pair, typ, setting, hazard])
    print("appended", len(rows), "to", path)
