import csv, os
COLS = ['id','writer','register','text','label','pair','type','setting','hazard']
def append(fn, rows):
    new = not os.path.exists(fn)
    with open(fn, 'a', newline='', encoding='utf-8') as f:
        w = csv.writer(f, quoting=csv.QUOTE_MINIMAL, lineterminator='\n')
        if new: w.writerow(COLS)
        for r in rows:
            assert len(r) == 9, r
            w.writerow(r)
