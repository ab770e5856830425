"""Tiny appender used by writer w10. Rows are typed by hand as literal tuples in each chunk script:
(register_code, text, label, pair_number_or_0, type, setting, hazard). This only assigns ids and writes CSV."""
import csv, os
REG = {'p': 'plain', 'f': 'first_person', 'c': 'context_command'}
COLS = ['id', 'writer', 'register', 'text', 'label', 'pair', 'type', 'setting', 'hazard']
def append(path, prefix, rows):
    exists = os.path.exists(path)
    n = 0
    if exists:
        with open(path, newline='', encoding='utf-8') as f:
            n = sum(1 for _ in csv.DictReader(f))
    with open(path, 'a', newline='', encoding='utf-8') as f:
        w = csv.writer(f)
        if not exists:
            w.writerow(COLS)
        for reg, text, label, pair, typ, setting, hazard in rows:
            n += 1
            w.writerow([f'{prefix}{n:04d}', 'w10', REG[reg], text, label,
                        f'w10-p{pair:03d}' if pair else '', typ, setting, hazard])
    print(path, 'rows now', n)
