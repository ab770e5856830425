import csv, os, sys
H=["id","writer","register","text","label","pair","type","setting","hazard"]
REG={"C":"code_plan","P":"plain"}
def add(path, prefix, rows):
    new = not os.path.exists(path)
    n = 0
    if not new:
        with open(path, newline="", encoding="utf-8") as f:
            n = sum(1 for _ in csv.DictReader(f))
    with open(path, "a", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        if new: w.writerow(H)
        for i, r in enumerate(rows):
            reg, text, label, pair, typ, setting, hazard = r
            w.writerow([f"w02-{prefix}{n+i+1:04d}", "w02", REG[reg], text.strip("\n"), label,
                        ("w02-"+pair) if pair else "", typ, setting, hazard])
    print(path, "now", n+len(rows))
