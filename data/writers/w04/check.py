import csv, sys, collections
H=['id','writer','register','text','label','pair','type','setting','hazard']
REG={'plain','numbered_plan','code_plan','operator_speech','first_person','context_command','scene_instruction','jailbreak_wrapper'}
TYP=set('plain minimal_pair negation condition polite_harmful justified_harmful safe_mentions_danger multi_step first_person deception privacy property dignity jailbreak order_matters earlier_step_makes_safe context_decides'.split())
allt=set(); ok=True
for fn in sys.argv[1:]:
    rows=list(csv.DictReader(open(fn,encoding='utf-8')))
    assert list(rows[0].keys())==H, rows[0].keys()
    ids=collections.Counter(r['id'] for r in rows)
    for k,v in ids.items():
        if v>1: print('DUP ID',k); ok=False
    pairs=collections.defaultdict(list)
    c=collections.Counter(); wc=[]
    for r in rows:
        if r['label'] not in ('0','1'): print('BAD LABEL',r['id']); ok=False
        if r['register'] not in REG: print('BAD REG',r['id']); ok=False
        if r['type'] not in TYP: print('BAD TYPE',r['id'],r['type']); ok=False
        if r['writer']!='w04' or not r['setting'] or not r['hazard']: print('BAD FIELD',r['id']); ok=False
        t=r['text'].strip()
        if t in allt: print('DUP TEXT',r['id']); ok=False
        allt.add(t)
        if r['pair']: pairs[r['pair']].append(r['label'])
        c[(r['register'],r['label'])]+=1
        if r['register']=='scene_instruction': wc.append(len(t.split()))
    for p,l in pairs.items():
        if sorted(l)!=['0','1']: print('BAD PAIR',p,l); ok=False
    n=len(rows); np_=sum(len(v) for v in pairs.values())
    print(fn,'rows',n,'pairs',len(pairs),'paired rows %.0f%%'%(100*np_/n))
    for k in sorted(c): print('  ',k,c[k])
    print('   labels', collections.Counter(r['label'] for r in rows))
    if wc: print('   scene words min/mean/max',min(wc),sum(wc)//len(wc),max(wc))
    print('   hazards',len(set(r['hazard'] for r in rows)),'settings',sorted(set(r['setting'] for r in rows)))
print('OK' if ok else 'PROBLEMS')
