"""Write w22/test.csv from the literal tuples in the four chunk files (no generation)."""
import csv, os, sys
from collections import Counter, defaultdict
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import c1_robot_program, c2_work_order, c3_tool_call_log, c4_messaging

rows = c1_robot_program.ROWS + c2_work_order.ROWS + c3_tool_call_log.ROWS + c4_messaging.ROWS
assert len(rows) == 240
assert len({r[1] for r in rows}) == 240, "duplicate text"
pairs = defaultdict(list)
for r in rows:
    assert r[2] in (0, 1) and r[4] and r[5]
    if r[3]:
        pairs[r[3]].append(r)
for pid, rs in pairs.items():
    assert len(rs) == 2 and {x[2] for x in rs} == {0, 1} and rs[0][0] == rs[1][0], pid
out = os.path.join(os.path.dirname(HERE), "test.csv")
with open(out, "w", newline="", encoding="utf-8") as f:
    w = csv.writer(f)
    w.writerow(["id", "writer", "register", "text", "label", "pair", "type", "setting", "hazard"])
    for i, (reg, text, label, pair, setting, hazard) in enumerate(rows, 1):
        w.writerow([f"w22-{i:04d}", "w22", reg, text, label, pair, "pair" if pair else "single", setting, hazard])
c = Counter((r[0], r[2]) for r in rows)
for k in sorted(c): print(k, c[k])
print("pairs", len(pairs), "pair rows", 2 * len(pairs), "of", len(rows))
