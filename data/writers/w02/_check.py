import csv, collections, hashlib
H=["id","writer","register","text","label","pair","type","setting","hazard"]
TYPES=set("plain minimal_pair negation condition polite_harmful justified_harmful safe_mentions_danger multi_step first_person deception privacy property dignity jailbreak order_matters earlier_step_makes_safe context_decides".split())
allr=[]
for fn in ["test.csv","train.csv"]:
    with open(fn, newline="", encoding="utf-8") as f:
        rd=csv.DictReader(f); assert rd.fieldnames==H, rd.fieldnames
        r=list(rd)
    allr+= [(fn,x) for x in r]
    print(fn, len(r), "labels", dict(collections.Counter(x["label"] for x in r)))
    print("  reg x label", sorted(collections.Counter((x["register"],x["label"]) for x in r).items()))
    assert all(x["label"] in ("0","1") for x in r)
    assert all(x["writer"]=="w02" for x in r)
    assert all(x["type"] in TYPES for x in r), [x["type"] for x in r if x["type"] not in TYPES]
    assert all(x["setting"] and x["hazard"] and x["text"] for x in r)
    p=collections.defaultdict(list)
    for x in r:
        if x["pair"]: p[x["pair"]].append(x)
    bad=[k for k,v in p.items() if len(v)!=2 or sorted(y["label"] for y in v)!=["0","1"] or v[0]["register"]!=v[1]["register"]]
    print("  pairs", len(p), "rows in pairs", sum(len(v) for v in p.values()), "bad", bad)
    print("  types", sorted(collections.Counter(x["type"] for x in r).items()))
    print("  hazards", len(set(x["hazard"] for x in r)), sorted(set(x["hazard"] for x in r)))
    print("  settings", sorted(collections.Counter(x["setting"] for x in r).items()))
ids=[x["id"] for _,x in allr]; texts=[x["text"].strip().lower() for _,x in allr]
print("ids unique", len(ids)==len(set(ids)), "texts unique", len(texts)==len(set(texts)))
tp=set(x["pair"] for f,x in allr if f=="test.csv" and x["pair"]); trp=set(x["pair"] for f,x in allr if f=="train.csv" and x["pair"])
print("pair ids shared across files:", tp & trp)
print("sha ok", hashlib.sha256(open("test.csv","rb").read()).hexdigest()==open("test.csv.sha256").read().split()[0])
