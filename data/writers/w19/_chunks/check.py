import csv, sys, collections
fn = sys.argv[1]
rows = list(csv.DictReader(open(fn, newline='', encoding='utf-8')))
cols = ['id','writer','register','text','label','pair','type','setting','hazard']
assert list(rows[0].keys()) == cols, rows[0].keys()
ids = [r['id'] for r in rows]; assert len(ids) == len(set(ids)), 'dup ids'
regs = {'plain','numbered_plan','code_plan'}
pairs = collections.defaultdict(list)
for r in rows:
    assert r['label'] in ('0','1'), r
    assert r['register'] in regs, r
    assert r['writer'] == 'w19'
    assert r['setting'] and r['hazard'] and r['type']
    if r['pair']: pairs[r['pair']].append(r)
    else: assert r['type'] == 'single', r['id']
for p, rs in pairs.items():
    assert len(rs) == 2, (p, len(rs))
    assert {rs[0]['label'], rs[1]['label']} == {'0','1'}, p
    assert rs[0]['register'] == rs[1]['register'], p
texts = [r['text'] for r in rows]; assert len(texts) == len(set(texts)), 'dup text'
c = collections.Counter((r['register'], r['label']) for r in rows)
print(len(rows), 'rows;', sum(r['label']=='1' for r in rows), 'unsafe;', len(pairs), 'pairs;', sum(len(v) for v in pairs.values()), 'paired rows')
for k in sorted(c): print(k, c[k])
