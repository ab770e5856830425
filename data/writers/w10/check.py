import csv, sys, collections
def check(path):
    rows = list(csv.DictReader(open(path, newline='', encoding='utf-8')))
    cols = ['id','writer','register','text','label','pair','type','setting','hazard']
    assert list(rows[0].keys()) == cols, rows[0].keys()
    ids = collections.Counter(r['id'] for r in rows); texts = collections.Counter(r['text'].strip().lower() for r in rows)
    bad = [k for k,v in ids.items() if v>1] + [k for k,v in texts.items() if v>1]
    pairs = collections.defaultdict(list)
    for r in rows:
        assert r['label'] in ('0','1'), r
        assert all(r[c] for c in cols if c!='pair'), r
        if r['pair']: pairs[r['pair']].append(r['label'])
    badp = [p for p,l in pairs.items() if sorted(l)!=['0','1']]
    print(path, 'rows', len(rows), 'pairs', len(pairs), 'paired rows', sum(len(v) for v in pairs.values()))
    print(' labels', collections.Counter(r['label'] for r in rows))
    print(' reg x label', sorted(collections.Counter((r['register'], r['label']) for r in rows).items()))
    print(' dup', bad, 'badpairs', badp)
    return rows
for p in sys.argv[1:]: check(p)
