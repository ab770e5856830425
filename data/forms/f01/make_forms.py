#!/usr/bin/env python3
"""f01 form rewriter: rewrites allowed training rows into machine-readable and buried forms.

Reads ONLY data/writers/w01..w12/train.csv and data/robot_train/part_a.csv, part_b.csv.
Deterministic: every random choice is drawn from an RNG seeded with (SEED, group, form, variant),
where group is the source pair id (or the row id for unpaired rows). Both members of a minimal pair
therefore get exactly the same template family and the same randomised parts; only the source text
(and so the deciding detail) differs. Stdlib only.

Usage: /work/main/.venv/bin/python data/forms/f01/make_forms.py
"""
import csv
import hashlib
import json
import os
import random
import re
import sys
from collections import Counter, defaultdict
from xml.sax.saxutils import escape as xesc, quoteattr

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, HERE)
from hand_rows import HAND  # noqa: E402

SEED = 20261201
MAXLEN = 1500
FORMS = ["json_program", "yaml_mission", "code_call", "behavior_tree", "pddl_goal", "buried_log"]
FORMS_PER_GROUP = 2


# ----------------------------------------------------------------------------- sources
def load_sources():
    rows = []
    for i in range(1, 13):
        w = "w%02d" % i
        with open(os.path.join(ROOT, "data", "writers", w, "train.csv"), newline="") as f:
            for r in csv.DictReader(f):
                r["source_writer"] = w
                rows.append(r)
    for p in ("a", "b"):
        with open(os.path.join(ROOT, "data", "robot_train", "part_%s.csv" % p), newline="") as f:
            for r in csv.DictReader(f):
                r["source_writer"] = "robot_train"
                rows.append(r)
    return rows


def rng_for(*parts):
    h = hashlib.sha256(("|".join(str(p) for p in (SEED,) + parts)).encode()).hexdigest()
    return random.Random(int(h[:16], 16))


# ----------------------------------------------------------------------------- parsing
STEP_RE = re.compile(r"^\s*(?:step\s*)?(\d{1,2})\s*[.):]\s+(.*\S)\s*$", re.I)
CODE_RE = re.compile(
    r"^\s*(#.*|[A-Za-z_][\w\.\[\]\"' ]*\s*=\s*.+|[A-Za-z_][\w\.]*\(.*\)?.*|for .+:|if .+:|else:|elif .+:|while .+:"
    r"|try:|except.*:|return.*|assert .+|with .+:|\)|\]|\}|[A-Z_]{3,}\s+\S.*|import .+|from .+ import .+|def .+:|await .+)\s*$")
CMD_RE = re.compile(r"^\s*(TASK|Task|Command|COMMAND|Instruction|INSTRUCTION|Instr|Request|User request|Operator)\s*:\s*(.*)$")


def is_code_line(ln):
    s = ln.strip()
    if not s:
        return True
    if not CODE_RE.match(ln):
        return False
    # prose sentences that happen to start like a call: require code punctuation
    if s.startswith("#"):
        return True
    return bool(re.search(r"[=\(\)\[\]_]|:$", s)) and not re.search(r"[a-z]+ [a-z]+ [a-z]+ [a-z]+ [a-z]+ [a-z]+\.$", s)


def parse(text):
    """Return dict(kind, ctx, steps, code, cmd, tail)."""
    lines = text.split("\n")
    steps, ctx, tail = [], [], []
    for ln in lines:
        m = STEP_RE.match(ln)
        if m:
            steps.append(m.group(2))
        elif steps:
            tail.append(ln)
        else:
            ctx.append(ln)
    if len(steps) >= 2 and not tail:
        return {"kind": "plan", "ctx": [c for c in ctx if c.strip()], "steps": steps}
    # code: a trailing block of code lines, optionally after prose lines
    nonblank = [ln for ln in lines if ln.strip()]
    codeflags = [is_code_line(ln) for ln in nonblank]
    if nonblank and any(codeflags):
        # first index from which everything is code
        k = len(nonblank)
        while k > 0 and codeflags[k - 1]:
            k -= 1
        code = nonblank[k:]
        prose = nonblank[:k]
        real = [c for c in code if not c.strip().startswith("#")]
        if real and any(re.search(r"[\(=]", c) for c in real) \
                and all(not codeflags[i] for i in range(k)):
            try:
                compile("\n".join(code), "<src>", "exec")
            except SyntaxError:
                return {"kind": "text"}  # a DSL line or pseudo-code: carried verbatim as text
            return {"kind": "code", "ctx": prose, "code": code}
    # context + command
    if len(nonblank) >= 2:
        m = CMD_RE.match(nonblank[-1])
        if m and m.group(2).strip():
            return {"kind": "ctxcmd", "ctx": nonblank[:-1], "cmd": m.group(2).strip()}
    return {"kind": "text"}


# ----------------------------------------------------------------------------- pools
ROBOTS = ["arm_01", "arm-02", "ur5e_left", "ur10e-bay3", "kinova_gen3_a", "panda_a", "panda-lab-2", "xarm7_k1",
          "ARM-3", "cobot_kit_2", "ward_arm_b", "rb-4", "franka_lab1", "yumi_r", "helper_arm", "tiago_arm",
          "stretch_02", "fetch-7", "kitchen_arm", "mobile_manip_5", "lite6-b", "jaco2", "doosan_m1013_1",
          "so100-home", "aloha_left", "piper_02", "arm.east", "hsr_03", "care_arm_4", "pick_cell_9"]
OPERATORS = ["j.okafor", "m.lind", "s.patel", "ops-night", "a.nowak", "t.reyes", "k.mensah", "l.dubois", "r.singh",
             "h.tanaka", "p.oconnor", "e.rossi", "d.kim", "f.haddad", "c.muller", "b.adeyemi", "n.ivanova",
             "g.santos", "y.chen", "o.berg", "planner", "supervisor_2", "remote_op", "shift_lead"]
PEOPLE = ["Priya", "Tom", "Grace", "Marek", "Aisha", "Leon", "Sofia", "Dan", "Mei", "Oscar", "Hannah", "Kwame",
          "Ines", "Raj", "Beth", "Yusuf", "Carla", "Niall", "Joanna", "Pete"]
SURN = ["Okafor", "Lind", "Patel", "Nowak", "Reyes", "Mensah", "Dubois", "Singh", "Tanaka", "Rossi", "Kim", "Haddad",
        "Muller", "Santos", "Chen", "Berg", "Walsh", "Novak", "Ahmed", "Fischer"]
SKILL_NAMES = ["execute_instruction", "run_nl_task", "nl_task", "do_task", "perform", "follow_instruction",
               "execute_text", "language_task", "exec_nl", "carry_out"]
FIELD_INSTR = ["instruction", "task", "text", "nl", "description", "command", "utterance", "prompt", "request",
               "goal_text", "nl_instruction", "task_text"]
FIELD_CTX = ["context", "situation", "scene", "notes", "background", "world_state", "observations", "preamble"]
PRIO = ["low", "normal", "normal", "high", "routine", "p2", "p3", "standard"]
SOURCES = ["planner_v2", "llm_planner", "voice_frontend", "ops_console", "tablet_app", "fleet_mgr", "scheduler",
           "web_ui", "nurse_station", "mes_bridge", "teleop_panel", "home_app"]


def ts(r, date=True):
    mo, d, h, m, s = r.randint(1, 12), r.randint(1, 28), r.randint(6, 22), r.randint(0, 59), r.randint(0, 59)
    if date:
        return "2026-%02d-%02dT%02d:%02d:%02d" % (mo, d, h, m, s)
    return "%02d:%02d:%02d" % (h, m, s)


def hexid(r, n=8):
    return "".join(r.choice("0123456789abcdef") for _ in range(n))


def ident(s, r=None, maxw=4):
    w = re.findall(r"[A-Za-z0-9]+", s.lower())[:maxw]
    return "_".join(w) or "task"


def verb_of(step):
    m = re.match(r"\s*([A-Za-z]+)", step)
    v = (m.group(1).lower() if m else "do")
    if v in ("the", "a", "an", "i", "my", "please", "and", "then", "if", "when", "while", "it", "this", "we", "you"):
        v = "do"
    return v


def setting_of(row):
    return (row.get("setting") or "site").strip().replace(" ", "_") or "site"


def typo(s, r, p=0.15):
    if r.random() > p:
        return s
    words = s.split(" ")
    cand = [i for i, w in enumerate(words) if len(w) > 4 and w.isalpha()]
    if not cand:
        return s
    i = r.choice(cand)
    w = words[i]
    j = r.randint(1, len(w) - 2)
    words[i] = w[:j] + w[j + 1] + w[j] + w[j + 2:]
    return " ".join(words)


def units(p, text):
    """Units of work: list of (label, text) in order; ctx lines are returned separately."""
    if p["kind"] == "plan":
        return p["ctx"], p["steps"]
    if p["kind"] == "ctxcmd":
        return p["ctx"], [p["cmd"]]
    return [], [text]


# ============================================================================= json_program
def jdump(obj, r):
    style = r.randint(0, 4)
    if style == 0:
        return json.dumps(obj, ensure_ascii=False)
    if style == 1:
        return json.dumps(obj, ensure_ascii=False, indent=2)
    if style == 2:
        return json.dumps(obj, ensure_ascii=False, indent=4)
    if style == 3:
        return json.dumps(obj, ensure_ascii=False, separators=(",", ":"))
    return json.dumps(obj, ensure_ascii=False, indent=1)


def shuffled_dict(items, r, keep_first=0):
    items = list(items)
    head, rest = items[:keep_first], items[keep_first:]
    r.shuffle(rest)
    return dict(head + rest)


def json_program(text, p, row, r, fam):
    robot, op = r.choice(ROBOTS), r.choice(OPERATORS)
    fi, fc = r.choice(FIELD_INSTR), r.choice(FIELD_CTX)
    ctx, us = units(p, text)
    sett = setting_of(row)
    if fam == 0:  # flat spec
        d = [("task_id", "T-%d" % r.randint(1000, 99999)), ("robot", robot), (fi, text), ("priority", r.choice(PRIO)),
             ("requested_by", op), ("created", ts(r))]
        return "```json\n" + jdump(shuffled_dict(d, r), r) + "\n```" if r.random() < 0.2 else jdump(shuffled_dict(d, r), r)
    if fam == 1:  # steps array
        stepk = r.choice(["steps", "plan", "actions", "sequence", "program"])
        sk = r.choice(["action", "skill", "op", "type"])
        tk = r.choice(["args", "params", "parameters", "with"])
        arr = []
        for i, u in enumerate(us):
            e = [("id", i + 1 if r.random() < 0.5 else "s%d" % (i + 1)), (sk, verb_of(u)), (tk, {r.choice(["text", "instruction", "detail", "nl"]): u})]
            arr.append(dict(e))
        d = [("program", "%s_%s" % (sett, hexid(r, 4))), ("robot", robot)]
        if ctx:
            d.append((fc, "\n".join(ctx)))
        d.append((stepk, arr))
        if r.random() < 0.5:
            d.append(("on_failure", r.choice(["abort", "stop_and_report", "retry_once", "ask_operator"])))
        return jdump(dict(d), r)
    if fam == 2:  # ROS 2 action goal on CLI
        act = r.choice(["/arm/execute_task", "/%s/nl_task" % robot.replace("-", "_").replace(".", "_"), "/task_server/execute", "/manipulation/run_instruction"])
        typ = r.choice(["ethimon_msgs/action/ExecuteTask", "arm_interfaces/action/NlTask", "task_msgs/action/RunInstruction", "planner_msgs/action/Execute"])
        key = r.choice(["task_text", "instruction", "description", "nl_goal"])
        body = {key: text, r.choice(["priority", "prio"]): r.randint(0, 5), "timeout_s": r.choice([60, 120, 300, 600, 900])}
        cmd = "ros2 action send_goal %s %s '%s'" % (act, typ, json.dumps(body, ensure_ascii=False).replace("'", "'\\''"))
        if r.random() < 0.4:
            cmd += " --feedback"
        if r.random() < 0.5:
            cmd = "$ " + cmd + "\nWaiting for an action server to become available...\nSending goal:"
        return cmd
    if fam == 3:  # fleet manager message
        hdr = {"msg_type": r.choice(["TASK_ASSIGN", "task.dispatch", "ASSIGN", "dispatch_request"]), "msg_id": hexid(r, 12),
               "stamp": ts(r) + "Z", "from": r.choice(SOURCES)}
        payload = {"robot_id": robot, "site": sett, "task": {r.choice(["kind", "category"]): "manipulation", fi: text,
                                                              "deadline": ts(r)}}
        if ctx and r.random() < 0.5:
            payload["task"] = {fc: "\n".join(ctx), fi: "\n".join(us), "deadline": ts(r)}
        d = {"header": hdr, "payload": payload} if r.random() < 0.6 else {"hdr": hdr, "body": payload}
        return jdump(d, r)
    if fam == 4:  # goal object nested params
        d = {"goal": {"type": r.choice(["nl_goal", "language_goal", "free_text", "operator_goal"]),
                      "spec": {"text": text, "lang": "en", "source": r.choice(SOURCES)}},
             "constraints": {"max_speed_scale": r.choice([0.2, 0.3, 0.5, 0.8]), "workspace": sett},
             "robot": robot}
        return jdump(shuffled_dict(d.items(), r), r)
    if fam == 5:  # planner output with reasoning-free plan and context
        d = {"planner": r.choice(["llm-planner", "saycan-lite", "task-gen", "mp-planner"]) + "/" + "%d.%d" % (r.randint(0, 3), r.randint(0, 12)),
             "input": {fi: text},
             "output": {"plan": [{"skill": r.choice(SKILL_NAMES), "arg": u} for u in us], "confidence": round(r.uniform(0.6, 0.99), 2)}}
        return jdump(d, r)
    if fam == 6:  # JSON lines queue
        lines = []
        n = r.randint(0, 2)
        for i, u in enumerate(us):
            lines.append(json.dumps({"seq": i + 1 + n, "robot": robot, "cmd": r.choice(SKILL_NAMES), "text": u}, ensure_ascii=False))
        pre = "// %s\n" % r.choice(["queue dump", "pending tasks", "tasks.jsonl", "queue/%s.jsonl" % robot]) if r.random() < 0.5 else ""
        if ctx:
            pre += json.dumps({"seq": n, "robot": robot, "cmd": "set_context", "text": "\n".join(ctx)}, ensure_ascii=False) + "\n"
        return pre + "\n".join(lines)
    if fam == 7:  # REST request
        path = r.choice(["/api/v1/tasks", "/v2/robots/%s/tasks" % robot, "/tasks", "/api/arm/jobs"])
        d = {fi: text, "robot": robot, "mode": r.choice(["auto", "supervised", "autonomous"])}
        return "POST %s HTTP/1.1\nHost: %s\nContent-Type: application/json\n\n%s" % (
            path, r.choice(["fleet.local", "10.0.%d.%d:8080" % (r.randint(0, 9), r.randint(2, 250)), "robot-gw", "localhost:5000"]), jdump(d, r))
    # fam 8: behaviour spec with preconditions (no invented safety facts, just metadata)
    d = {"spec_version": r.choice(["1.0", "0.3", "2"]), "name": ident(us[0]),
         "preconditions": [r.choice(["arm_homed", "gripper_ok", "estop_released"])],
         "body": [{"do": u} for u in us], "postconditions": ["report_done"]}
    if ctx:
        d["given"] = ctx
    return jdump(d, r)


# ============================================================================= yaml_mission
def yq(s, r, indent):
    """YAML scalar: plain when safe, else double-quoted, block scalar for multi-line."""
    if "\n" in s:
        pad = " " * (indent + 2)
        return "|\n" + "\n".join(pad + ln if ln.strip() else "" for ln in s.split("\n"))
    plain_ok = (not re.search(r":\s|\s#|^[\-?:,\[\]\{\}#&*!|>'\"%@`]|:$", s)) and not re.match(r"^(yes|no|true|false|null|~|\d)", s, re.I)
    if plain_ok and r.random() < 0.6:
        return s
    if "'" not in s and r.random() < 0.3:
        return "'" + s + "'"
    return json.dumps(s, ensure_ascii=False)


def yaml_mission(text, p, row, r, fam):
    robot, op = r.choice(ROBOTS), r.choice(OPERATORS)
    ctx, us = units(p, text)
    sett = setting_of(row)
    fi, fc = r.choice(FIELD_INSTR), r.choice(FIELD_CTX)
    ind = r.choice([2, 2, 4])
    I = " " * ind
    if fam == 0:
        out = ["mission:", I + "id: m-%s" % hexid(r, 6), I + "robot: %s" % robot, I + "site: %s" % sett, I + "steps:"]
        for u in us:
            out.append(I + "- %s: %s" % (r.choice(["do", "action", "task"]), yq(u, r, ind * 2)))
        if ctx:
            out.insert(4, I + "%s: %s" % (fc, yq("\n".join(ctx), r, ind)))
        return "\n".join(out)
    if fam == 1:  # block scalar instruction
        return "\n".join(["# mission file generated %s" % ts(r)[:10] if r.random() < 0.5 else "---",
                          "name: %s" % ident(us[0]), "robot: %s" % robot, "priority: %s" % r.choice(PRIO),
                          "%s: |" % fi] + [I + ln for ln in text.split("\n")] + ["on_error: %s" % r.choice(["halt", "notify", "abort"])])
    if fam == 2:  # k8s-like CRD
        out = ["apiVersion: robots.%s/v1%s" % (r.choice(["example.org", "fleet.local", "lab.internal", "ethi.dev"]), r.choice(["", "beta1", "alpha2"])),
               "kind: %s" % r.choice(["ArmTask", "ManipulationJob", "RobotMission"]), "metadata:",
               I + "name: %s-%s" % (ident(us[0], maxw=3).replace("_", "-"), hexid(r, 5)), I + "namespace: %s" % sett.replace("_", "-"),
               "spec:", I + "robotRef: %s" % robot]
        if ctx:
            out.append(I + "%s: %s" % ("context", yq("\n".join(ctx), r, ind)))
        out.append(I + "instructions:")
        for u in us:
            out.append(I + "- " + yq(u, r, ind * 2))
        return "\n".join(out)
    if fam == 3:  # ansible-like playbook
        out = ["- name: %s" % r.choice(["arm tasks", "shift job", "queued request", "operator job"]), "  hosts: %s" % robot,
               "  gather_facts: %s" % r.choice(["false", "no"]), "  tasks:"]
        if ctx:
            out.append("    - name: load context")
            out.append("      arm.set_context:")
            out.append("        text: " + yq("\n".join(ctx), r, 8))
        for i, u in enumerate(us):
            out.append("    - name: step %d" % (i + 1))
            out.append("      arm.%s:" % r.choice(["nl_task", "instruction", "run"]))
            out.append("        text: " + yq(u, r, 8))
        return "\n".join(out)
    if fam == 4:  # recipe
        listy = r.random() < 0.5
        out = ["recipe: %s" % ident(us[0], maxw=5), "version: %d" % r.randint(1, 9), "author: %s" % op, "procedure:"]
        for i, u in enumerate(us):
            out.append(I + "%d: %s" % (i + 1, yq(u, r, ind)) if not listy else I + "- step: %d\n%s  text: %s" % (i + 1, I, yq(u, r, ind * 2)))
        if ctx:
            out.insert(3, "notes: " + yq("\n".join(ctx), r, 0))
        return "\n".join(out)
    if fam == 5:  # flow style
        if ctx:
            return "%s: {robot: %s, %s: %s, %s: [%s]}" % (r.choice(["job", "task", "mission"]), robot, fc,
                                                        json.dumps("\n".join(ctx), ensure_ascii=False), r.choice(["steps", "do"]),
                                                        ", ".join(json.dumps(u, ensure_ascii=False) for u in us))
        return "%s: {robot: %s, %s: %s, at: \"%s\"}" % (r.choice(["job", "task", "mission"]), robot, fi, json.dumps(text, ensure_ascii=False), ts(r, False))
    if fam == 6:  # queue of tasks with other routine ones
        routine = r.sample(["wipe down work surface", "return tools to rack", "home the arm", "run gripper self-test",
                            "charge to 80 percent", "log shift summary", "refill paper towel dispenser", "scan shelf barcodes"], 2)
        items = [("routine", routine[0]), ("req", text), ("routine", routine[1])]
        if r.random() < 0.5:
            items = [items[1], items[0], items[2]] if r.random() < 0.3 else items
        out = ["queue:"]
        for k, (kind, s) in enumerate(items):
            out.append(I + "- id: %d" % (k + 1))
            out.append(I + "  %s: %s" % (fi, yq(s, r, ind + 2)))
            out.append(I + "  robot: %s" % robot)
        return "\n".join(out)
    if fam == 7:  # behaviour mission with context/command keys
        out = ["---", "robot: %s" % robot, "location: %s" % sett]
        if ctx:
            out.append("%s:" % fc)
            for c in ctx:
                out.append(I + "- " + yq(c, r, ind))
        out.append("%s:" % r.choice(["command", "commands", "todo"]))
        for u in us:
            out.append(I + "- " + yq(u, r, ind))
        out.append("requested_by: %s" % op)
        return "\n".join(out)
    # fam 8: ros2 params-like
    out = ["%s:" % robot.replace("-", "_").replace(".", "_"), I + "ros__parameters:", I * 2 + "mission:",
           I * 3 + "%s: %s" % (fi, yq(text, r, ind * 3)), I * 3 + "speed_scale: %s" % r.choice(["0.3", "0.5", "0.25", "1.0"])]
    return "\n".join(out)


# ============================================================================= code_call
def pylit(s, r):
    if "\n" in s and '"""' not in s and not s.endswith('"') and "\\" not in s:
        return '"""' + s + '"""'
    if "'" in s and '"' not in s:
        return '"' + s + '"'
    if '"' in s and "'" not in s and r.random() < 0.7:
        return "'" + s + "'"
    return json.dumps(s, ensure_ascii=False)


def comment(lines, prefix="# "):
    return "\n".join(prefix + ln if ln.strip() else prefix.rstrip() for ln in lines)


def code_call(text, p, row, r, fam):
    robot = r.choice(ROBOTS)
    var = r.choice(["robot", "arm", "bot", "r", "ctrl", "manip", "cobot"])
    fn = r.choice(SKILL_NAMES)
    ctx, us = units(p, text)
    if p["kind"] == "code":
        # the source is already a program: keep it verbatim, bury it in a policy wrapper
        code = p["code"]
        hdr = comment(p["ctx"]) + "\n" if p["ctx"] else ""
        k = fam % 4
        if k == 0:
            body = "\n".join("    " + ln for ln in code)
            fname = r.choice(["run", "policy", "main", "task", "job_%s" % hexid(r, 4)])
            return "%sdef %s(%s):\n%s\n\n\n%s(connect(%s))" % (hdr, fname, var, body, fname, json.dumps(robot))
        if k == 1:
            return "%sfrom %s import *\n%s\n%s\n%s" % (
                hdr, r.choice(["robot_api", "arm_skills", "cap_lib", "skills", "policies.prims"]),
                r.choice(["# --- generated by planner ---", "# begin", "# code-as-policies output", "# cell %d" % r.randint(1, 40)]),
                "\n".join(code), r.choice(["done()", "report('ok')", "arm.home()", "log('finished')"]))
        if k == 2:
            return (hdr + "".join((">>> %s\n" if not ln.startswith(" ") else "... %s\n") % ln for ln in code)).rstrip()
        body = "\n".join("        " + ln for ln in code)
        return "%sclass %s(Task):\n    robot = %s\n\n    def run(self):\n%s" % (
            hdr, r.choice(["Job", "OperatorTask", "PlannedTask", "Step%d" % r.randint(1, 9)]), json.dumps(robot), body)
    if fam == 0:
        head = r.choice(["# task from %s" % r.choice(SOURCES), "# operator request", "# %s" % ts(r), "# queued"])
        return "%s\n%s = connect(%s)\n%s.%s(%s)" % (head, var, json.dumps(robot), var, fn, pylit(text, r))
    if fam == 1:
        name = r.choice(["task", "job", "do_request", "handle_%s" % ident(us[0], maxw=2), "step_%d" % r.randint(1, 30)])
        doc = text.replace("\\", "\\\\")
        return 'def %s(%s):\n    """%s"""\n    %s.%s(%s.__doc__)' % (name, var, doc.replace("\n", "\n    ") if '"""' not in doc else doc, var, fn, name)
    if fam == 2:
        out = []
        if ctx:
            out.append(comment(ctx))
        for u in us:
            out.append("%s.%s(%s)" % (var, fn, pylit(u, r)))
        return "\n".join(out)
    if fam == 3:
        out = []
        cv, pv = r.choice(["context", "scene", "ctx"]), r.choice(["plan", "steps", "todo"])
        if ctx:
            out.append("%s = %s" % (cv, pylit("\n".join(ctx), r)))
        out.append("%s = [" % pv)
        for u in us:
            out.append("    %s," % pylit(u, r))
        out.append("]")
        out.append("for s in %s:\n    %s.%s(s%s)" % (pv, var, fn, ", context=%s" % cv if ctx else ""))
        return "\n".join(out)
    if fam == 4:
        return "from %s import %s\n\n%s = %s(%s, host=%s)\n# %s\n%s.%s(%s)" % (
            r.choice(["robot_api", "armkit", "fleet.client", "cobot_sdk"]), r.choice(["Arm", "Robot", "Manipulator"]), var,
            r.choice(["Arm", "Robot", "Manipulator"]), json.dumps(robot), json.dumps("10.0.%d.%d" % (r.randint(0, 9), r.randint(2, 250))),
            r.choice(["request below comes from the ops console", "sent by %s" % r.choice(OPERATORS), "ticketless request"]),
            var, fn, pylit(text, r))
    if fam == 5:
        return "async def main():\n    async with %s(%s) as %s:\n        await %s.submit(%s(%s=%s, priority=%s))\n\nasyncio.run(main())" % (
            r.choice(["FleetClient", "ArmSession", "RobotLink"]), json.dumps(robot), var, var, r.choice(["Task", "Job", "NlTask"]),
            r.choice(["description", "text", "instruction"]), pylit(text, r), json.dumps(r.choice(PRIO)))
    if fam == 6:
        lg = r.choice(["log", "logger", "LOG"])
        out = ["%s.info(%s)" % (lg, json.dumps("starting " + r.choice(["job", "request", "task"]) + " " + hexid(r, 6)))]
        if ctx:
            out.append("%s.set_context(%s)" % (var, pylit("\n".join(ctx), r)))
        for u in us:
            out.append("ok = %s.skills.call(%s, args={%s: %s})" % (var, json.dumps(r.choice(SKILL_NAMES)), json.dumps(r.choice(["utterance", "text", "instruction"])), pylit(u, r)))
            out.append("assert ok, %s" % json.dumps("step failed"))
        return "\n".join(out)
    if fam == 7:  # code-as-policies prompt cell: comment query then calls
        out = ["# query: " + us[0] if len(us) == 1 and not ctx and "\n" not in us[0] else comment(["query:"] + text.split("\n"))]
        out.append("objs = %s()" % r.choice(["detect_objects", "get_obj_names", "perceive"]))
        out.append("%s(%s, objs=objs)" % (r.choice(["execute_task", "plan_and_execute", "ground_and_run"]), r.choice(["query", "QUERY"])))
        return "\n".join(out)
    # fam 8: dict-driven dispatcher
    return "%s = {\n    \"robot\": %s,\n    \"%s\": %s,\n}\ndispatch(%s)" % (
        r.choice(["req", "request", "job"]), json.dumps(robot), r.choice(FIELD_INSTR), pylit(text, r), r.choice(["req", "request", "job"]))


# ============================================================================= behavior_tree
def bt_comment(s):
    s = s.replace("--", "- -")
    return "<!-- " + s + " -->"


def behavior_tree(text, p, row, r, fam):
    robot = r.choice(ROBOTS)
    ctx, us = units(p, text)
    if p["kind"] == "code":
        ctx, us = p["ctx"], p["code"]
    node = r.choice(["ExecuteInstruction", "NlTask", "RunSkill", "LanguageAction", "DoStep", "PerformTask", "ArmTask"])
    attr = r.choice(["text", "instruction", "task", "command", "goal"])
    treeid = r.choice(["MainTree", "Task", "Job_%s" % hexid(r, 4), ident(us[0], maxw=3).title().replace("_", "")])
    ind = r.choice(["  ", "    ", "\t"])
    if fam in (0, 1, 2, 3):
        fmt = '<root BTCPP_format="4"%s>' % (' main_tree_to_execute="%s"' % treeid if r.random() < 0.6 else "") if fam in (0, 2) else '<root main_tree_to_execute="%s">' % treeid
        out = [fmt, ind + '<BehaviorTree ID="%s">' % treeid]
        d = 2
        wrap = None
        if fam == 2:
            wrap = r.choice(['RetryUntilSuccessful num_attempts="%d"' % r.randint(2, 4), 'Timeout msec="%d"' % r.choice([30000, 60000, 120000])])
            out.append(ind * d + "<%s>" % wrap)
            d += 1
        out.append(ind * d + "<Sequence%s>" % (' name="%s"' % r.choice(["main", "steps", "job", "seq"]) if r.random() < 0.5 else ""))
        d += 1
        if ctx:
            if fam == 1 or r.random() < 0.5:
                for c in ctx:
                    out.append(ind * d + bt_comment(c))
            else:
                out.append(ind * d + '<SetBlackboard output_key="%s" value=%s/>' % (r.choice(["context", "scene"]), quoteattr("\n".join(ctx))))
        for u in us:
            if p["kind"] == "code" and u.strip().startswith("#"):
                out.append(ind * d + bt_comment(u.strip().lstrip("#").strip()))
            elif p["kind"] == "code":
                out.append(ind * d + "<Script code=%s/>" % quoteattr(u.strip()))
            elif fam == 3:
                out.append(ind * d + '<Action ID="%s" %s=%s/>' % (node, attr, quoteattr(u)))
            else:
                out.append(ind * d + "<%s %s=%s robot=\"%s\"/>" % (node, attr, quoteattr(u), robot) if r.random() < 0.3 else ind * d + "<%s %s=%s/>" % (node, attr, quoteattr(u)))
        d -= 1
        out.append(ind * d + "</Sequence>")
        if wrap:
            d -= 1
            out.append(ind * d + "</%s>" % wrap.split(" ")[0])
        out.append(ind + "</BehaviorTree>")
        if fam == 3 and r.random() < 0.7:
            out += [ind + "<TreeNodesModel>", ind * 2 + '<Action ID="%s">' % node, ind * 3 + '<input_port name="%s"/>' % attr,
                    ind * 2 + "</Action>", ind + "</TreeNodesModel>"]
        out.append("</root>")
        return "\n".join(out)
    if fam == 4:  # SMACH
        out = ["sm = smach.StateMachine(outcomes=['succeeded', 'aborted'])"]
        if ctx:
            out.insert(0, comment(ctx))
        out.append("with sm:")
        for i, u in enumerate(us):
            nxt = "STEP_%d" % (i + 2) if i + 1 < len(us) else "succeeded"
            out.append("    smach.StateMachine.add('STEP_%d', %s(%s), transitions={'succeeded': '%s', 'aborted': 'aborted'})" % (
                i + 1, r.choice(["NlState", "ExecuteText", "SkillState", "TaskState"]), pylit(u, r), nxt))
        out.append("outcome = sm.execute()")
        return "\n".join(out)
    if fam == 5:  # plain-text state machine listing
        out = ["STATE MACHINE %s (robot=%s)" % (treeid, robot)]
        if ctx:
            out.append("  context: " + " / ".join(ctx))
        for i, u in enumerate(us):
            nxt = "S%d" % (i + 2) if i + 1 < len(us) else "DONE"
            out.append("  S%d [%s] %s\n      on success -> %s ; on fail -> %s" % (i + 1, r.choice(["exec", "action", "run"]), json.dumps(u, ensure_ascii=False), nxt, r.choice(["ABORT", "SAFE_STOP", "REPORT"])))
        out.append("  DONE [final]")
        return "\n".join(out)
    if fam == 6:  # py_trees
        out = ["root = py_trees.composites.Sequence(name=%s, memory=True)" % json.dumps(treeid)]
        if ctx:
            out.insert(0, comment(ctx))
        out.append("root.add_children([")
        for u in us:
            out.append("    %s(name=%s, %s=%s)," % (node, json.dumps(verb_of(u)), attr, pylit(u, r)))
        out.append("])")
        out.append("tree = py_trees.trees.BehaviourTree(root)")
        return "\n".join(out)
    if fam == 7:  # tree dump
        out = ["[-] %s [Sequence]" % treeid]
        if ctx:
            out.append("    [o] Blackboard context = " + " ".join(ctx))
        for i, u in enumerate(us):
            br = "└──" if i == len(us) - 1 else "├──"
            out.append("    %s %s: %s" % (br, node, u.replace("\n", " ")) + (" [%s]" % r.choice(["IDLE", "RUNNING", "IDLE"]) if r.random() < 0.5 else ""))
        return "\n".join(out)
    # fam 8: SCXML
    out = ['<scxml xmlns="http://www.w3.org/2005/07/scxml" version="1.0" initial="s1">']
    if ctx:
        out.append("  " + bt_comment(" ".join(ctx)))
    for i, u in enumerate(us):
        nxt = "s%d" % (i + 2) if i + 1 < len(us) else "done"
        out.append('  <state id="s%d">' % (i + 1))
        out.append('    <onentry><send event="%s"><param name="text" expr=%s/></send></onentry>' % (node, quoteattr("'" + u.replace("'", "\\'") + "'")))
        out.append('    <transition event="done.%s" target="%s"/>' % (node, nxt))
        out.append("  </state>")
    out.append('  <final id="done"/>')
    out.append("</scxml>")
    return "\n".join(out)


# ============================================================================= pddl_goal
def pcom(s, prefix="; "):
    return "\n".join(prefix + ln for ln in s.split("\n"))


def pddl_goal(text, p, row, r, fam):
    robot = r.choice(ROBOTS).replace("_", "-").replace(".", "-").lower()
    sett = setting_of(row).replace("_", "-")
    ctx, us = units(p, text)
    if p["kind"] == "code":
        ctx, us = p["ctx"], ["\n".join(p["code"])]
    dom = r.choice(["%s-arm" % sett, "manip-%s" % sett, "household", "arm-tasks", "service-arm", "%s-ops" % sett])
    prob = "%s-%s" % (r.choice(["task", "job", "p", "req"]), hexid(r, 4))
    stepobjs = ["s%d" % (i + 1) for i in range(len(us))]
    pred = r.choice(["done", "completed", "achieved", "executed"])
    if fam in (0, 1, 2):
        out = []
        if fam == 0:
            out.append(pcom(text))
        out += ["(define (problem %s)" % prob, "  (:domain %s)" % dom,
                "  (:objects %s - robot %s - step)" % (robot, " ".join(stepobjs)),
                "  (:init (at %s home) (handempty %s)%s)" % (robot, robot, "".join(" (next %s %s)" % (a, b) for a, b in zip(stepobjs, stepobjs[1:])))]
        if fam == 1:
            if ctx:
                out.insert(0, pcom("\n".join(ctx)))
            for s, u in zip(stepobjs, us):
                out.append(pcom("%s: %s" % (s, u), "  ; "))
        if fam == 2:
            out.insert(0, ";; planner request %s from %s" % (ts(r), r.choice(SOURCES)))
            out.insert(1, pcom(text, ";; NL: "))
        out.append("  (:goal (and %s)))" % " ".join("(%s %s)" % (pred, s) for s in stepobjs))
        return "\n".join(out)
    if fam == 3:  # planner trace
        out = [pcom(text, r.choice(["; task: ", "; NL> ", "; instruction: "])),
               "; %s" % r.choice(["plan found", "solution found", "Found plan"]) + " in %.2fs, cost %d" % (r.uniform(0.01, 2.5), len(us))]
        for i, (s, u) in enumerate(zip(stepobjs, us)):
            out.append("%d.000: (%s %s %s)   ; %s" % (i, r.choice(["execute-step", "do", "run-skill"]), robot, s, u.replace("\n", " ") if len(us) > 1 else "step %d" % (i + 1)))
        return "\n".join(out)
    if fam == 4:  # fast-downward-like
        out = ["task_nl = " + json.dumps(text, ensure_ascii=False), "Solution found!", "Actual search time: %.5fs [t=%.5fs]" % (r.uniform(0, 0.1), r.uniform(0, 0.2))]
        for s in stepobjs:
            out.append("execute-step %s %s (1)" % (robot, s))
        out.append("Plan length: %d step(s)." % len(stepobjs))
        out.append("Plan cost: %d" % len(stepobjs))
        return "\n".join(out)
    if fam == 5:  # HDDL task network
        out = ["(define (problem %s) (:domain %s)" % (prob, dom), "  (:objects %s - robot)" % robot, "  (:htn :parameters ()",
               "    :subtasks (and"]
        for i, u in enumerate(us):
            out.append("      (t%d (%s %s %s))" % (i + 1, r.choice(["do-nl-task", "perform", "carry-out"]), robot, json.dumps(u, ensure_ascii=False)))
        out.append("    )")
        if len(us) > 1:
            out.append("    :ordering (and %s))" % " ".join("(< t%d t%d)" % (i + 1, i + 2) for i in range(len(us) - 1)))
        else:
            out[-1] += ")"
        if ctx:
            out.insert(0, pcom("\n".join(ctx)))
        out.append("  (:init (at %s home)))" % robot)
        return "\n".join(out)
    if fam == 6:  # LLM+P style
        return "%s\n%s\n\nPDDL goal:\n(:goal (and %s))" % (
            r.choice(["Natural language task:", "NL task:", "Task (NL):", "Instruction:"]), text,
            " ".join("(%s %s)" % (pred, s) for s in stepobjs))
    if fam == 7:  # problem with metadata string
        return "(define (problem %s)\n  (:domain %s)\n  (:metadata (%s %s) (requested-by %s))\n  (:objects %s - robot)\n  (:init (ready %s))\n  (:goal (%s nl-task-1)))" % (
            prob, dom, r.choice(["instruction", "nl-goal", "description"]), json.dumps(text, ensure_ascii=False), r.choice(OPERATORS).replace(".", "-"), robot, robot, pred)
    # fam 8: planner log
    hh, mm, ss = r.randint(6, 21), r.randint(0, 58), r.randint(0, 50)
    t = ["%02d:%02d:%02d" % (hh, mm, ss + k) for k in range(4)]
    out = ["[%s] planner: received goal from %s" % (t[0], r.choice(SOURCES)),
           pcom(text, "[goal.nl] "),
           "[%s] planner: grounding %d action(s), domain=%s" % (t[1], len(us), dom),
           "[%s] planner: goal = (and %s)" % (t[2], " ".join("(%s %s)" % (pred, s) for s in stepobjs)),
           "[%s] planner: dispatching to %s" % (t[3], robot)]
    return "\n".join(out)


# ============================================================================= buried_log
LOG_ROUTINE = [
    "heartbeat ok", "battery at {b}%", "joint {j} temperature {t:.1f} C nominal", "gripper self-test passed",
    "camera extrinsics unchanged (err {e:.2f} px)", "map update received ({n} cells)", "wifi rssi -{w} dBm",
    "torque sensors zeroed", "firmware check: up to date", "cpu load {c}%", "disk usage {c}%", "clock sync ok (offset {o} ms)",
    "e-stop circuit test ok", "vacuum pump idle", "tool changer locked", "force/torque bias updated", "navigation idle",
    "charging dock reachable", "log rotation done", "remaining queue: {q} task(s)", "skill library loaded ({n} skills)",
    "collision model refreshed", "speech frontend idle", "door sensor closed (store room)", "lights schedule applied",
    "ping fleet manager ok ({o} ms)", "arm homed", "payload estimate 0.{j}{q} kg", "depth camera fps {f}", "backup uploaded",
]
SERVICES = ["planner", "task_server", "arm_ctl", "perception", "fleet_agent", "watchdog", "power_mgr", "nav2", "speech", "logger"]
EMAIL_ROUTINE = [
    "Timesheets are due by Friday noon, please.", "The coffee machine on level 2 has been fixed.",
    "Reminder that the car park will be resurfaced next week.", "Thanks for covering the late shift on Tuesday.",
    "The new printer is set up in room B; the code is on the noticeboard.", "Could everyone update their contact details in the portal?",
    "The team lunch moved to Thursday.", "Invoices for last month have been sent to accounts.",
    "Please return any borrowed extension leads to the store room.", "We are out of A4 paper until Monday's delivery.",
    "The window cleaners come on Wednesday morning.", "The wifi password changes on the first of the month.",
    "Minutes of last meeting are attached.", "Holiday requests for August by the end of the month, please.",
    "Training slots for the new tablet app are on the shared calendar.", "The plants in reception need repotting at some point.",
]
REPORT_ROUTINE = [
    "Restocked gloves and paper towels.", "Charged both tablets.", "Swept the entrance.", "Checked the notice board.",
    "Emptied recycling.", "Arm ran its morning self-test: no faults.", "Updated the inventory sheet.",
    "Watered the plants in reception.", "Filed delivery notes.", "Wiped down the counters.", "Replaced the label roll.",
    "Logged fridge temperature: 4 C.", "Returned the trolley to bay 2.", "Sorted the post.", "Cleaned the camera lens.",
]


TODO_ROUTINE = [
    "Restock the glove dispenser.", "Return the trolley to bay 2.", "Wipe down the counters.", "Sort the post.",
    "Run the evening self-test.", "Charge to 80 percent before close.", "Update the inventory sheet.", "Water the plants in reception.",
    "Empty the recycling.", "Clean the camera lens.", "Replace the label roll.", "File the delivery notes.",
]


def fill(s, r):
    return s.format(b=r.randint(35, 99), j=r.randint(1, 7), t=r.uniform(28, 45), e=r.uniform(0.1, 0.9), n=r.randint(12, 4000),
                    w=r.randint(40, 80), c=r.randint(3, 85), o=r.randint(1, 40), q=r.randint(0, 9), f=r.choice([15, 30, 60]))


def buried_log(text, p, row, r, fam):
    robot = r.choice(ROBOTS)
    target = r.randint(500, MAXLEN - 20)
    t0 = [r.randint(6, 20), r.randint(0, 59), r.randint(0, 59)]
    def tick():
        t0[2] += r.randint(1, 50)
        if t0[2] >= 60:
            t0[2] -= 60; t0[1] += 1
        if t0[1] >= 60:
            t0[1] -= 60; t0[0] += 1
        return "%02d:%02d:%02d" % tuple(t0)
    date = ts(r)[:10]
    if fam in (0, 1, 2):  # controller / syslog / ROS console
        lvl = ["INFO", "INFO", "INFO", "DEBUG"]
        mday = "%s %2d" % (r.choice(["Jan", "Mar", "May", "Jul", "Sep", "Nov"]), r.randint(1, 28))
        pids = {sv: r.randint(300, 9000) for sv in SERVICES}
        epoch = [r.randint(1730000000, 1790000000)]
        def line(msg, svc=None):
            svc = svc or r.choice(SERVICES)
            if fam == 0:
                return "%sT%s.%03dZ %s %s %s" % (date, tick(), r.randint(0, 999), r.choice(lvl), svc, typo(msg, r))
            if fam == 1:
                return "%s %s %s[%d]: %s" % (mday, tick(), robot, pids.get(svc, 0), typo(msg, r))
            epoch[0] += r.randint(1, 40)
            return "[%s] [%d.%09d] [%s]: %s" % (r.choice(lvl), epoch[0], r.randint(0, 999999999), svc, typo(msg, r))
        tl = text.split("\n")
        cont = " " * r.choice([4, 8]) if r.random() < 0.5 else "    | "
        intro = r.choice(["new task received: ", "task accepted: ", "goal text = ", "instruction from %s: " % r.choice(SOURCES), "queued request: "])
        body = tl[0] + "".join("\n" + cont + x for x in tl[1:])
        room = max(0, target - len(body) - 60)
        nb, na = r.randint(2, 7), r.randint(2, 6)
        while (nb + na) * 62 > room and (nb > 1 or na > 1):
            if nb >= na and nb > 1:
                nb -= 1
            else:
                na -= 1
        before = [line(fill(r.choice(LOG_ROUTINE), r)) for _ in range(nb)]
        block = line(intro, "task_server") + body
        after = [line(r.choice(["planning...", "plan accepted, executing", "step 1 started", "validating request"]), "task_server")]
        after += [line(fill(r.choice(LOG_ROUTINE), r)) for _ in range(na - 1)]
        return "\n".join(before + [block] + after)
    if fam in (3, 4):  # email thread
        names = r.sample(PEOPLE, 3)
        sur = r.sample(SURN, 3)
        dom = r.choice(["example.org", "ward7.nhs.example", "fleet.local", "site.example.com", "mail.home"])
        def mail(n, s, body, subj):
            return "From: %s %s <%s.%s@%s>\nDate: %s %s\nSubject: %s\n\n%s" % (n, s, n.lower(), s.lower(), dom, date, tick(), subj, body)
        subj = r.choice(["Re: this week", "Re: rota + arm jobs", "Fwd: odds and ends", "Re: Tuesday", "Re: housekeeping"])
        m1 = mail(names[0], sur[0], "Hi all,\n%s\n%s" % (typo(r.choice(EMAIL_ROUTINE), r), r.choice(["Cheers", "Thanks", "Best"])), subj.replace("Re: ", ""))
        m2 = mail(names[1], sur[1], "%s\n\n%s\n%s\n\n%s\n%s" % (
            r.choice(["Thanks %s." % names[0], "Noted.", "Will do.", "Hi %s," % names[0]]), typo(r.choice(EMAIL_ROUTINE), r),
            r.choice(["One more for the arm's queue today:", "Can we add this to the robot's list:", "Task for %s:" % robot,
                      "Please put this on the arm's job list:"]), text, r.choice(["Ta", "Thanks", names[1]])), subj)
        m3 = mail(names[2], sur[2], "%s\n%s" % (typo(r.choice(EMAIL_ROUTINE), r), r.choice(["Regards", "Thanks", "x"])), subj)
        out = "\n\n-----\n".join([m3, m2, m1]) if fam == 3 else "\n\n".join([m1, "> " + m2.replace("\n", "\n> "), m3])
        if len(out) > MAXLEN:
            out = "\n\n-----\n".join([m2, m1])
        return out
    if fam in (5, 6):  # daily status report
        title = r.choice(["Daily status report", "Shift summary", "Status update", "End-of-morning report", "Site status"])
        done = r.sample(REPORT_ROUTINE, r.randint(3, 6))
        later = r.sample(TODO_ROUTINE, r.randint(1, 3)) if fam == 5 else r.sample([x for x in REPORT_ROUTINE if x not in done], r.randint(1, 3))
        bul = r.choice(["- ", "* ", "• "])
        if fam == 5:
            sec = [title + " - " + robot + " - " + date, "", "Done:"] + [bul + typo(x, r) for x in done] + [
                "", r.choice(["Next for the arm:", "Queued for this afternoon:", "Assigned to the arm:", "To do:"])]
            sec.append("\n".join(("  " if i else bul) + x for i, x in enumerate(text.split("\n"))))
            sec += [bul + x for x in later] + ["", "Issues: " + r.choice(["none", "none", "wheel 3 squeaks", "tablet battery weak"])]
        else:
            sec = ["%s (%s)" % (title, date), "Battery %d%%, uptime %dh." % (r.randint(20, 99), r.randint(1, 200)),
                   " ".join(typo(x, r) for x in done[:3]),
                   r.choice(["Request passed on for the arm: ", "New instruction for the arm: ", "Also asked today: "]) + text,
                   " ".join(later), "Next report at %02d:00." % r.randint(12, 20)]
        out = "\n".join(sec)
        return out
    if fam == 7:  # meeting minutes with action items
        names = r.sample(PEOPLE, 4)
        items = ["%s: %s" % (names[1], r.choice(["chase the supplier", "update the rota", "book the engineer", "renew the parking permits"])),
                 "%s: %s" % (r.choice(["Arm", "Robot (%s)" % robot, robot]), text),
                 "%s: %s" % (names[2], r.choice(["circulate minutes", "order more labels", "fix the notice board", "check the fire extinguisher dates"]))]
        out = ["Minutes - %s %s" % (r.choice(["team meeting", "morning huddle", "ops stand-up", "weekly catch-up"]), date),
               "Present: " + ", ".join(names), "", "1. " + typo(r.choice(EMAIL_ROUTINE), r), "2. " + typo(r.choice(EMAIL_ROUTINE), r), "",
               "Action items:"] + ["  - " + x for x in items] + ["", "Next meeting: %s" % r.choice(["Monday", "Thursday 9:30", "next week"])]
        return "\n".join(out)
    # fam 8: CSV-ish event export
    rows = ["time,source,event,detail"]
    nb, na = r.randint(2, 5), r.randint(2, 5)
    for _ in range(nb):
        rows.append("%s,%s,status,%s" % (tick(), r.choice(SERVICES), fill(r.choice(LOG_ROUTINE), r).replace(",", ";")))
    rows.append("%s,%s,task,%s" % (tick(), r.choice(SOURCES), json.dumps(text, ensure_ascii=False)))
    for _ in range(na):
        rows.append("%s,%s,status,%s" % (tick(), r.choice(SERVICES), fill(r.choice(LOG_ROUTINE), r).replace(",", ";")))
    return "\n".join(rows)


RENDER = {"json_program": json_program, "yaml_mission": yaml_mission, "code_call": code_call,
          "behavior_tree": behavior_tree, "pddl_goal": pddl_goal, "buried_log": buried_log}
NFAM = 9


# ============================================================================= main
def main():
    src = load_sources()
    groups = defaultdict(list)
    for row in src:
        groups[row["pair"] or ("solo:" + row["source_writer"] + ":" + row["id"])].append(row)
    out = []
    # hand rows first (they take precedence on duplicate texts)
    srcidx = {(r["source_writer"], r["id"]): r for r in src}
    for (sid, sw, form, label, relab, text) in HAND:
        s = srcidx[(sw, sid)]
        assert str(label) == s["label"] or relab, (sid, sw)
        out.append({"source_id": sid, "source_writer": sw, "form": form, "method": "hand", "text": text.strip("\n"),
                    "label": str(label), "pair": (s["pair"] + "-" + form + "-h1") if s["pair"] else "",
                    "type": s["type"], "setting": s["setting"], "hazard": s["hazard"], "relabelled": "1" if relab else "0"})
    form_load = Counter()
    for gk in sorted(groups):
        members = groups[gk]
        r0 = rng_for(gk, "forms")
        order = FORMS[:]
        r0.shuffle(order)
        # prefer the currently least-used forms so forms stay balanced
        order.sort(key=lambda f: form_load[f] + r0.random() * 40)
        made = 0
        for form in order:
            if made >= FORMS_PER_GROUP:
                break
            rf = rng_for(gk, form, "fam")
            fam = rf.randrange(NFAM)
            texts = []
            for m in members:
                r = rng_for(gk, form, fam, "parts")  # identical draws for both pair members
                t = RENDER[form](m["text"], parse(m["text"]), m, r, fam)
                texts.append(t)
            if any(len(t) > MAXLEN for t in texts) or len(set(texts)) < len(texts):
                continue
            for m, t in zip(members, texts):
                out.append({"source_id": m["id"], "source_writer": m["source_writer"], "form": form, "method": "template",
                            "text": t, "label": m["label"], "pair": (m["pair"] + "-" + form + "-v%d" % (fam + 1)) if m["pair"] else "",
                            "type": m["type"], "setting": m["setting"], "hazard": m["hazard"], "relabelled": "0"})
            form_load[form] += len(members)
            made += 1
    # de-duplicate texts; a dropped row takes its pair partner with it
    seen, drop_pairs, keep = set(), set(), []
    for o in out:
        if o["text"] in seen:
            if o["pair"]:
                drop_pairs.add(o["pair"])
            o["_drop"] = True
        seen.add(o["text"])
    final = [o for o in out if not o.get("_drop") and not (o["pair"] and o["pair"] in drop_pairs)]
    with open(os.path.join(HERE, "train.csv"), "w", newline="") as f:
        w = csv.writer(f)
        cols = ["id", "writer", "source_id", "source_writer", "form", "method", "text", "label", "pair", "type", "setting", "hazard", "relabelled"]
        w.writerow(cols)
        for i, o in enumerate(final):
            o["id"] = "f01-%06d" % (i + 1)
            o["writer"] = "f01"
            w.writerow([o[c] for c in cols])
    c = Counter((o["form"], o["label"], o["method"]) for o in final)
    print(len(final), "rows; dropped dup", len(out) - len(final))
    for k in sorted(c):
        print(k, c[k])


if __name__ == "__main__":
    main()
