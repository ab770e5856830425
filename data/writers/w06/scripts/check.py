import csv, sys, collections
path = sys.argv[1]
rows = list(csv.DictReader(open(path, encoding="utf-8")))
cols = ["id","writer","register","text","label","pair","type","setting","hazard"]
assert list(rows[0].keys()) == cols, rows[0].keys()
REG = {"plain","numbered_plan","code_plan","operator_speech","first_person","context_command","scene_instruction","jailbreak_wrapper"}
TYP = set("plain minimal_pair negation condition polite_harmful justified_harmful safe_mentions_danger multi_step first_person deception privacy property dignity jailbreak order_matters earlier_step_makes_safe context_decides".split())
errs = []
ids = collections.Counter(r["id"] for r in rows)
errs += [f"dup id {k}" for k,v in ids.items() if v>1]
txt = collections.Counter(r["text"].strip().lower() for r in rows)
errs += [f"dup text {k[:60]}" for k,v in txt.items() if v>1]
pairs = collections.defaultdict(list)
for r in rows:
    if r["label"] not in ("0","1"): errs.append(f"label {r['id']}")
    if r["register"] not in REG: errs.append(f"reg {r['id']}")
    if r["type"] not in TYP: errs.append(f"type {r['id']} {r['type']}")
    if r["writer"] != "w06": errs.append(f"writer {r['id']}")
    for c in ("setting","hazard","text"):
        if not r[c].strip(): errs.append(f"empty {c} {r['id']}")
    if r["pair"]: pairs[r["pair"]].append(r["label"])
for p, ls in pairs.items():
    if len(ls)!=2 or sorted(ls)!=["0","1"]: errs.append(f"pair {p} {ls}")
print("rows", len(rows), "labels", collections.Counter(r["label"] for r in rows))
c = collections.Counter((r["register"], r["label"]) for r in rows)
for reg in sorted({r["register"] for r in rows}):
    print(f"  {reg:18s} n={c[(reg,'0')]+c[(reg,'1')]:4d}  1={c[(reg,'1')]}  0={c[(reg,'0')]}")
paired = sum(1 for r in rows if r["pair"])
print("pairs", len(pairs), "paired rows", paired, f"{paired/len(rows):.0%}")
print("hazards", len({r['hazard'] for r in rows}), "settings", len({r['setting'] for r in rows}))
print("ERRORS", errs if errs else "none")
