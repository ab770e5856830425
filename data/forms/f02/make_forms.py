"""f02 form generator: rewrites allowed source rows into human / conversational forms.

Deterministic (seeded per source pair / row and form), stdlib only.
Run:  /work/main/.venv/bin/python data/forms/f02/make_forms.py   (from the repo root)
Reads: data/writers/w01..w12/train.csv, data/robot_train/part_a.csv, part_b.csv
Writes: data/forms/f02/train.csv  (template rows + the hand rows in hand_rows.py)
"""
import csv
import hashlib
import os
import random
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", ".."))
sys.dont_write_bytecode = True
sys.path.insert(0, HERE)
from hand_rows import HAND  # noqa: E402

SEED = "f02-forms-v1"
MAXLEN = 1500
FORMS = ["multi_turn_chat", "sms", "speech_transcript", "code_switched",
         "euphemism", "alarming_safe", "greeting_wrapped"]


def rng_for(*keys):
    h = hashlib.sha256(("|".join([SEED] + [str(k) for k in keys])).encode()).hexdigest()
    return random.Random(int(h[:16], 16))


# ----------------------------------------------------------------------------- sources
def load_sources():
    rows = []
    for i in range(1, 13):
        w = "w%02d" % i
        with open(os.path.join(ROOT, "data", "writers", w, "train.csv"), newline="") as f:
            for r in csv.DictReader(f):
                r["sw"] = w
                rows.append(r)
    for p in ("part_a", "part_b"):
        with open(os.path.join(ROOT, "data", "robot_train", p + ".csv"), newline="") as f:
            for r in csv.DictReader(f):
                r["sw"] = "robot_train"
                r["register"] = "robot"
                rows.append(r)
    return rows


# ----------------------------------------------------------------------------- parsing
REQ_RE = re.compile(r"^\s*(Instruction|Command|TASK|Task|Request|Action|Instr)\s*:\s*(.*)$", re.I)
CTX_PREFIX = re.compile(r"^\s*(Scene|Context|Caption(\s*\([^)]*\))?|Thinking|Goal|Task)\s*:\s*", re.I)
STEP_RE = re.compile(r"^\s*(?:Step\s*)?(\d+)\s*[.):]\s+(.*)$")
BULLET_RE = re.compile(r"^\s*[-*\u2022]\s+(.*)$")
SPEAKER_RE = re.compile(r"^([A-Z][A-Za-z.' ]{1,24}):\s+(\S.*)$")
CONTROL_RE = re.compile(r"^\s*(if|for|while|else|elif|def|try|with|except|return)\b", re.M)


def is_code(line):
    s = line.strip()
    if not s:
        return False
    if s.startswith("#"):
        return True
    if re.match(r"^[A-Za-z_][\w.\[\]\"']*\s*\(.*\)\s*(#.*)?$", s):
        return True
    if re.match(r"^[A-Za-z_][\w.\[\]\"']*\s*=[^=].*", s) and ("(" in s or "_" in s or re.search(r"=\s*[\d\"'\[]", s)):
        return True
    if re.match(r"^[A-Za-z_]\w*(\.\w+)+\s*\(", s):
        return True
    if re.match(r"^[A-Z_]{3,}\b", s) and ";" not in s and ("=" in s or "_" in s):
        return True
    return False


def _words(ident):
    return ident.replace("_", " ").replace(".", " ").strip()


KW = {"target": "to", "dest": "to", "destination": "to", "location": "at", "loc": "at", "place": "at", "obj": "",
      "item": "", "object": "", "what": "", "where": "at", "position": "at", "pos": "at", "x": "", "name": "",
      "recipient": "to", "person": "for", "patient": "for", "who": "for"}
UNITS = set("ml mg kg g mm cm m s sec secs seconds minutes mins min hours h c deg degrees percent l litres mL units".split())


def kwarg(k, v=None):
    if k in KW:
        return " " + KW[k] + " "
    return " " + _words(k) + " "


def code_expr(s):
    s = s.strip()
    # unit keywords: ml=2 -> 2 ml
    s = re.sub(r"\b(%s)\s*=\s*([\d.]+)" % "|".join(sorted(UNITS, key=len, reverse=True)), r"\2 \1", s)
    s = re.sub(r"\bTrue\b", "yes", s)
    s = re.sub(r"\bFalse\b", "no", s)
    s = re.sub(r"\bNone\b", "none", s)
    s = s.replace("!=", " is not ").replace("==", " is ").replace(">=", " at least ").replace("<=", " at most ")
    # string literals: drop quotes, underscores to spaces
    s = re.sub(r"\"([^\"]*)\"|'([^']*)'", lambda m: (m.group(1) if m.group(1) is not None else m.group(2)).replace("_", " "), s)
    s = re.sub(r",\s*(\w+)\s*=\s*", lambda m: kwarg(m.group(1)), s)
    s = re.sub(r"\(\s*(\w+)\s*=\s*", lambda m: kwarg(m.group(1)), s)
    s = re.sub(r"([A-Za-z_\)\]])\.([A-Za-z_])", r"\1 \2", s)   # obj.method -> words; decimals (7.5) kept
    s = re.sub(r"\)\s*\.(\w)", r") \1", s)
    s = s.replace("(", " ").replace(")", " ").replace("[", " ").replace("]", " ").replace("{", " ").replace("}", " ")
    s = s.replace("_", " ")
    s = re.sub(r"\s+,", ",", s)
    s = re.sub(r"\s+", " ", s).strip(" ,")
    return s


def code_line(line):
    s = line.rstrip()
    note = ""
    m = re.search(r"\s#\s*(.*)$", s)
    if m and not s.strip().startswith("#"):
        note = m.group(1).strip()
        s = s[:m.start()]
    s = s.strip()
    m = re.match(r"^([A-Za-z_][\w.\[\]\"']*)\s*=\s*(.+)$", s)
    if m and not m.group(2).startswith("="):
        lhs, rhs = m.group(1), m.group(2)
        if "(" in rhs and re.match(r"^[\w.]+\s*\(", rhs.strip()):
            out = code_expr(rhs)
        else:
            out = "set " + code_expr(lhs) + " to " + code_expr(rhs)
    elif re.match(r"^[A-Z_]{3,}\s", s):
        out = code_expr(s.replace(" = ", " to "))
        out = out[0].lower() + out[1:]
    else:
        out = code_expr(s)
    if note:
        out = out + " (" + note + ")"
    return out


def parse(r):
    """Return dict(ctx=[...], steps=[...], speaker, voice, kind) or None to skip."""
    text = r["text"].replace("\r", "")
    sw, reg = r["sw"], r.get("register", "")
    if sw == "w09" and not re.match(r"^\s*(Context|Caption)", text):
        return None
    if re.match(r"^\s*(Scene|Context)\s*:\s*[{\[]", text):
        return None
    if reg == "code_plan" and CONTROL_RE.search(text):
        return None
    lines = [l for l in text.split("\n") if l.strip()]
    ctx, steps, speaker = [], [], ""
    voice = "robot" if sw == "w12" else "user"
    kind = "plain"
    # explicit request line
    req_idx = None
    for i, l in enumerate(lines):
        if REQ_RE.match(l):
            req_idx = i
    if req_idx is not None and REQ_RE.match(lines[req_idx]).group(1).lower() in ("task", "instr") and req_idx != len(lines) - 1:
        req_idx = None
    if req_idx is not None:
        for l in lines[:req_idx]:
            l2 = CTX_PREFIX.sub("", l).strip()
            if l2:
                ctx.append(l2)
        req = REQ_RE.match(lines[req_idx]).group(2).strip()
        rest = lines[req_idx + 1:]
        steps = [req] if req else []
        for l in rest:
            m = STEP_RE.match(l) or BULLET_RE.match(l)
            steps.append((m.group(m.lastindex) if m else l).strip())
        kind = "ctx_req"
    else:
        code_mode = reg == "code_plan" or any(is_code(l) for l in lines)
        for l in lines:
            m = STEP_RE.match(l)
            b = BULLET_RE.match(l)
            if m:
                st = m.group(2).strip()
                steps.append(code_line(st) if is_code(st) else st)
                kind = "plan"
            elif b:
                steps.append(b.group(1).strip())
                kind = "plan"
            elif code_mode and is_code(l):
                if l.strip().startswith("#"):
                    c = l.strip().lstrip("#").strip()
                    if steps:
                        steps[-1] = steps[-1] + " (" + c + ")"
                    else:
                        ctx.append(c)
                else:
                    steps.append(code_line(l))
                kind = "code"
            else:
                l2 = CTX_PREFIX.sub("", l).strip()
                if steps:
                    steps.append(l2)
                else:
                    ctx.append(l2)
        if not steps:
            # a single block of prose: last line is the request
            if len(ctx) >= 2:
                steps = [ctx.pop()]
            else:
                one = ctx.pop() if ctx else text.strip()
                sents = split_sents(one)
                if len(sents) >= 2 and len(one) > 60:
                    ctx = sents[:-1]
                    steps = [sents[-1]]
                else:
                    steps = [one]
    if not steps:
        return None
    m = SPEAKER_RE.match(steps[0])
    if m and not (len(m.group(1).split()) <= 3 and all(w[0].isupper() for w in m.group(1).split())):
        m = None
    if m and m.group(1).split()[0] not in ("Note", "Goal", "Action", "Then", "Plan", "Step", "Warning", "Mode", "Debug", "Task", "Rule", "Reminder"):
        speaker = m.group(1).strip()   # kept in the text; only the chat form moves it into the turn label
    steps = [s for s in steps if s]
    ctx = [c for c in ctx if c]
    # leftover machine syntax (inline JSON, API calls) belongs to other writers' forms: skip the row
    if any(re.search(r"[{}]|\w\(\w*=|\w\(\"|=\s*\"|\w+\.\w+\(|->|==", x) for x in ctx + steps):
        return None
    return dict(ctx=ctx, steps=steps, speaker=speaker, voice=voice, kind=kind)


def split_sents(t):
    parts = re.split(r"(?<=[.!?])\s+(?=[A-Z\"'])", t.strip())
    return [p.strip() for p in parts if p.strip()]


def end_punct(s):
    s = s.strip()
    return s if s[-1:] in ".!?:;)\"'" else s + "."


LOWER_OK = set()   # filled in main(): words seen more often lower-case than capitalised mid-sentence


def lc_first(s):
    if len(s) > 1 and s[0].isupper() and not s[1].isupper():
        first = re.match(r"[A-Za-z']+", s)
        if first and (first.group(0).lower() in LOWER_OK or first.group(0).lower() in COMMON_START) and first.group(0) != "I":
            return s[0].lower() + s[1:]
    return s


def uc_first(s):
    return s[0].upper() + s[1:] if s and s[0].islower() else s


def build_vocab(rows):
    from collections import Counter
    lo, up = Counter(), Counter()
    for r in rows:
        for w in re.findall(r"(?<=[a-z,;] )([A-Za-z']+)", r["text"]):
            (lo if w[0].islower() else up)[w.lower()] += 1
    for w, n in lo.items():
        if n > 2 * up[w]:
            LOWER_OK.add(w)


IMPERATIVE_BLOCK = set("i i'm i've i'll we we're he she it they there this that my our his her their the a an mr mrs ms dr "
                       "its it's he's she's they're you you're your hi hello hey ok okay so as since because if when once while "
                       "after before no not nobody someone everyone".split())


def imperative_start(s):
    m = re.match(r"[A-Za-z']+", s.strip())
    return bool(m) and m.group(0).lower() in LOWER_OK and m.group(0).lower() not in IMPERATIVE_BLOCK


def split_imperative(p):
    """Move leading non-imperative sentences of the request into the context so a frame can wrap an imperative."""
    ctx, steps = list(p["ctx"]), list(p["steps"])
    if imperative_start(steps[0]):
        return ctx, steps, True
    sents = split_sents(steps[0])
    for i in range(1, len(sents)):
        if imperative_start(sents[i]):
            return ctx + sents[:i], [" ".join(sents[i:])] + steps[1:], True
    return ctx, steps, False


COMMON_START = set("""put take bring give move place open close turn switch pour hand set fill leave
pick lift carry fetch get make wipe clean tidy wash dry heat cool cut chop slice check read tell send
let lock unlock push pull drive stack store throw bin empty tip load unload run start stop hold show
drop add mix spray plug unplug hang go use keep label write change swap help feed serve sort fold
photograph scan copy print shred delete remove wind lower raise press reset disable enable grab
collect wheel stand sit lay rinse scrub replace top warm boil fry bake microwave lean shut seal
follow record film look measure weigh count decant weld grind sand drill saw tie strap
the a an this that it now please then if when once after before while since as and but so
there he she they we you my our his her their its""".split())


def utter(p, style="prose", rng=None, joiner=None):
    """Render a parsed row as one spoken/written utterance (user voice)."""
    ctx = [uc_first(end_punct(c)) for c in p["ctx"]]
    steps = p["steps"]
    if len(steps) == 1:
        body = end_punct(steps[0])
    else:
        j = joiner or (rng.choice(["then", "then", "and then", "after that", "next"]) if rng else "then")
        if style == "list":
            body = " ".join("%d) %s" % (i + 1, end_punct(s)) for i, s in enumerate(steps))
        elif style == "lines":
            body = "\n".join(end_punct(s) for s in steps)
        else:
            parts = [steps[0].rstrip(".")]
            for s in steps[1:]:
                parts.append(j + " " + lc_first(s.rstrip(".")))
            body = ", ".join(parts) + "."
    body = uc_first(body)
    return (" ".join(ctx) + " " + body).strip() if ctx else body


# ----------------------------------------------------------------------------- pools
USERS = ["Sam", "Priya", "Tomasz", "Aisha", "Ben", "Mei", "Oluwaseun", "Grace", "Diego", "Hannah", "Raj", "Lotte",
         "Kwame", "Sofia", "Jonas", "Fatima", "Liam", "Nadia", "Chen", "Eve", "Marco", "Ines", "Tariq", "Ruth",
         "Yusuf", "Claire", "Ana", "Pete", "Leila", "Owen", "Bea", "Hiro"]
ROBOTS = ["Arm-2", "ROBO", "Kit", "Tilly", "helper-arm", "UR5e-kitchen", "Max", "bot", "Rosie", "cell-3 arm",
          "Jaco", "Robbie", "Assist-1", "Panda", "Nova", "homebot"]
CHAT_LABELS = [("User", "Robot"), ("user", "assistant"), ("U", "R"), ("operator", "arm"), ("Me", "{robot}"),
               ("{user}", "{robot}"), ("H", "R"), ("human", "robot"), ("> you", "> {robot}")]


def ts(rng, fmt=None):
    h, m, s = rng.randint(6, 22), rng.randint(0, 59), rng.randint(0, 59)
    fmt = fmt or rng.choice(["%02d:%02d", "[%02d:%02d]", "%d:%02d", "%02d:%02d:%02d"])
    if fmt.count("%") == 3:
        return fmt % (h, m, s)
    return fmt % (h, m)


# ----------------------------------------------------------------------------- multi_turn_chat
ACK_CTX = ["Okay, noted.", "Got it.", "Understood.", "Right, I've got that.", "Thanks, noted.", "OK.",
           "Noted. Go on.", "Mm-hm, I see.", "Copy that.", "Alright, understood. What do you need?",
           "I've logged that. Anything else?", "Okay. What would you like me to do?"]
OPEN_USER = ["hey {robot}", "{robot}, you there?", "Hi {robot}.", "hello", "are you free for a minute?", "ok robot",
             "quick one", "{robot}?", "Morning {robot}.", "can you help me with something", "yo {robot}"]
OPEN_ROBOT = ["Yes, I'm here.", "Ready.", "Listening.", "Hello! How can I help?", "Yes? I'm listening.",
              "I'm free. What do you need?", "Standing by.", "Hi! What can I do for you?", "Here. Go ahead."]
ASK_ROBOT = ["What would you like me to do?", "What's the task?", "Okay, what should I do?", "Sure. What exactly?",
             "And what do you need from me?", "Understood. Instructions?", "Right. What's next?", "Okay, go on."]
NEXT_ROBOT = ["Done. Next?", "Okay, what next?", "Done that. Then?", "Finished. What else?", "Okay. And after that?",
              "Completed. Next step?", "Done. Anything else?"]
FILLER_Q = [("how's your battery?", "Battery at {pct}%."), ("are you still calibrated?", "Yes, calibration checked at {t}."),
            ("did you finish the last job?", "Yes, all done."), ("can you hear me ok?", "Yes, loud and clear."),
            ("is the gripper working again?", "Yes, the gripper passed its self-test."),
            ("are you plugged in?", "I'm at {pct}%, that's enough for now."),
            ("what are you doing right now?", "Nothing queued. I'm idle."),
            ("you busy?", "No, my queue is empty.")]
GO_AHEAD = ["Yes, go ahead: {a}", "ok do it. {a}", "Fine. {a}", "Right, so: {a}", "Yep, that's the plan. {a}",
            "Agreed, {a}", "Go on then. {a}", "Sounds right. {a}", "Correct. Please {a}", "yes exactly, {a}"]
OP2_ASK = ["ok what do you need it to do?", "sure, what's the job?", "right, and?", "go on", "what should I tell the arm?",
           "okay, what do you want it doing?", "yep, I'm at the console", "kk what's the task"]


def r_chat(p, rng, row):
    robot, user = rng.choice(ROBOTS), rng.choice(USERS)
    if p.get("speaker"):
        user = p["speaker"]
    ul, rl = rng.choice(CHAT_LABELS)
    if p.get("speaker"):
        ul = "{user}"
        st0 = p["steps"][0]
        if st0.startswith(p["speaker"] + ":"):
            p = dict(p, steps=[st0[len(p["speaker"]) + 1:].strip()] + p["steps"][1:])
    ul, rl = ul.format(user=user, robot=robot), rl.format(user=user, robot=robot)
    sep = rng.choice([": ", ": ", " - ", ": "])
    turns = []
    ctx, steps = p["ctx"], p["steps"]
    if p["voice"] == "robot":
        # robot reasons aloud about the job, human confirms with the action
        fam = rng.randint(0, 3)
        reasoning = " ".join(end_punct(c) for c in ctx) if ctx else ""
        act = utter(dict(ctx=[], steps=steps), style=rng.choice(["prose", "list"]), rng=rng)
        if fam == 0 and reasoning:
            turns = [(rl, reasoning + " " + rng.choice(["Shall I go ahead?", "What should I do?", "Please confirm the plan.", "How do you want me to proceed?"])),
                     (ul, rng.choice(GO_AHEAD).format(a=lc_first(act)))]
        elif fam == 1 and reasoning:
            turns = [(ul, rng.choice(OPEN_USER).format(robot=robot)), (rl, rng.choice(OPEN_ROBOT)),
                     (rl, "Here's my read of the situation: " + reasoning),
                     (ul, rng.choice(GO_AHEAD).format(a=lc_first(act)))]
        elif fam == 2 and reasoning:
            turns = [(rl, "Status: " + reasoning), (ul, rng.choice(["ok", "right", "i see", "mm", "ok thanks"])),
                     (rl, rng.choice(ASK_ROBOT)), (ul, act)]
        else:
            turns = [(ul, rng.choice(OPEN_USER).format(robot=robot)), (rl, (reasoning + " " if reasoning else "") + rng.choice(ASK_ROBOT)),
                     (ul, act)]
    else:
        fam = rng.randint(0, 7)
        if not ctx and len(steps) == 1:
            fam = rng.choice([0, 1, 6, 7])
        if fam == 0:
            turns = [(ul, rng.choice(OPEN_USER).format(robot=robot)), (rl, rng.choice(OPEN_ROBOT)), (ul, utter(p, rng=rng))]
        elif fam == 1:
            q, a = rng.choice(FILLER_Q)
            turns = [(ul, q), (rl, a.format(pct=rng.randint(35, 98), t=ts(rng, "%02d:%02d"))), (ul, utter(p, rng=rng))]
        elif fam == 2:
            turns = [(ul, " ".join(end_punct(c) for c in ctx) or rng.choice(OPEN_USER).format(robot=robot)),
                     (rl, rng.choice(ACK_CTX)), (ul, utter(dict(ctx=[], steps=steps), rng=rng))]
        elif fam == 3 and len(steps) >= 2 and len(steps) <= 3:
            first = (" ".join(end_punct(c) for c in ctx) + " " if ctx else "") + "First, " + lc_first(end_punct(steps[0]))
            turns = [(ul, first)]
            for s in steps[1:]:
                turns.append((rl, rng.choice(NEXT_ROBOT)))
                turns.append((ul, end_punct(s)))
        elif fam == 4 and ctx:
            # two operators, then one of them relays to the arm
            a, b = rng.sample(USERS, 2)
            if p.get("speaker"):
                a = p["speaker"]
            stamp = rng.random() < 0.6
            t0 = rng.randint(7, 21) * 60 + rng.randint(0, 50)

            def lab(n, k):
                return ("[%02d:%02d] " % divmod(t0 + k, 60) if stamp else "") + n
            turns = [(lab(a, 0), " ".join(end_punct(c) for c in ctx)), (lab(b, 1), rng.choice(OP2_ASK)),
                     (lab(a, 2), utter(dict(ctx=[], steps=steps), rng=rng))]
            sep = rng.choice([": ", ": ", " > "])
        elif fam == 5 and ctx:
            turns = [(ul, rng.choice(OPEN_USER).format(robot=robot)), (rl, rng.choice(OPEN_ROBOT))]
            groups = [ctx] if len(ctx) == 1 else [ctx[:len(ctx) // 2], ctx[len(ctx) // 2:]]
            for grp in groups[:1]:
                turns.append((ul, " ".join(end_punct(c) for c in grp)))
                turns.append((rl, rng.choice(ACK_CTX)))
            if len(groups) > 1:  # second half of the context goes with the request (never dropped)
                turns.append((ul, " ".join(end_punct(c) for c in groups[1]) + " " + utter(dict(ctx=[], steps=steps), rng=rng)))
                turns[-1] = (ul, turns[-1][1].strip())
                groups = None
            if groups is not None:
                turns.append((ul, utter(dict(ctx=[], steps=steps), rng=rng)))
        elif fam == 6:
            turns = [(rl, rng.choice(["Task complete. Anything else?", "I've finished the previous job.", "Idle. Awaiting instructions.",
                                      "Good %s. What can I do?" % rng.choice(["morning", "afternoon", "evening"])])),
                     (ul, utter(p, rng=rng))]
        else:
            turns = [(ul, utter(p, rng=rng)), (rl, rng.choice(["Just to confirm, you want me to do that now?", "Confirm: execute that?",
                                                               "Before I start: is that the full instruction?", "Shall I start now?",
                                                               "Do you want me to do exactly that?"])),
                     (ul, rng.choice(["yes, now please", "Yes. Exactly that.", "yep", "Confirmed.", "yes go", "Yes, thanks.", "correct"]))]
    assert len(turns) <= 6, turns
    layout = rng.randint(0, 3)
    if layout == 0:
        return "\n".join(a + sep + b for a, b in turns)
    if layout == 1:
        return "\n\n".join(a + sep + b for a, b in turns)
    if layout == 2:
        t0 = rng.randint(7, 21) * 3600 + rng.randint(0, 3000)
        out = []
        for k, (a, b) in enumerate(turns):
            t0 += rng.randint(4, 40)
            t = t0
            if a.startswith("["):
                out.append(a + sep + b)
            else:
                out.append("%02d:%02d:%02d %s%s%s" % (t // 3600, t // 60 % 60, t % 60, a, sep, b))
        return "\n".join(out)
    return "\n".join(("[%s]" % a if not a.startswith(("[", ">")) else a) + " " + b for a, b in turns)


# ----------------------------------------------------------------------------- sms
SMS_MAP = [(r"\byou\b", ["u"]), (r"\byour\b", ["ur", "yr"]), (r"\bplease\b", ["pls", "plz", "pls"]),
           (r"\bthanks\b", ["thx", "ta", "thnx"]), (r"\bthank you\b", ["ty", "thank u"]), (r"\bbecause\b", ["cos", "bc", "coz"]),
           (r"\bbefore\b", ["b4"]), (r"\btomorrow\b", ["tmrw", "2moro"]), (r"\btonight\b", ["2nite", "tonite"]),
           (r"\bminutes\b", ["mins"]), (r"\bminute\b", ["min"]), (r"\bwith\b", ["w/", "with"]), (r"\bwithout\b", ["w/o", "without"]),
           (r"\band\b", ["&", "n", "and"]), (r"\bokay\b", ["ok", "k"]), (r"\babout\b", ["abt"]), (r"\bpeople\b", ["ppl"]),
           (r"\bsomething\b", ["smth", "sth"]), (r"\bmessage\b", ["msg"]), (r"\bare\b", ["r"]), (r"\bright now\b", ["rn"]),
           (r"\bdo not\b", ["dont", "don't"]), (r"\bdon't\b", ["dont"]), (r"\bcan't\b", ["cant"]), (r"\bdoesn't\b", ["doesnt"]),
           (r"\bit's\b", ["its"]), (r"\bI'm\b", ["im", "Im"]), (r"\bthat's\b", ["thats"]), (r"\bwon't\b", ["wont"]),
           (r"\bisn't\b", ["isnt"]), (r"\bthrough\b", ["thru"]), (r"\bbetween\b", ["btwn"]), (r"\bhave\b", ["hav", "have"]),
           (r"\bjust\b", ["jst", "just"]), (r"\btemperature\b", ["temp"]), (r"\bkitchen\b", ["kitchen", "kitch"])]
TYPO_OK = ["the", "and", "just", "with", "from", "that", "this", "then", "when", "there", "table", "kitchen", "could",
           "would", "again", "after", "thing", "quick", "leave", "bring", "first"]
SMS_OPEN = ["", "", "", "hey ", "hi ", "yo ", "{robot} ", "{robot} - ", "urgent: ", "quick one: ", "hiya ", "ok so ", "btw "]
SMS_CLOSE = ["", "", "", " thx", " ty", " pls", " cheers", " x", " :)", " asap", " ta", " k thx", " 👍", " ok?", " !!"]


def smsify(t, rng):
    t = t.replace("\n", " ").strip()
    for pat, subs in SMS_MAP:
        if rng.random() < 0.75:
            t = re.sub(pat, lambda m: rng.choice(subs), t, flags=re.I)
    # drop some articles
    if rng.random() < 0.6:
        t = re.sub(r"\b(the|a) (?=\w)", lambda m: "" if rng.random() < 0.45 else m.group(0), t)
    if rng.random() < 0.8:
        t = t.lower() if rng.random() < 0.8 else t
    # punctuation loss
    if rng.random() < 0.7:
        t = re.sub(r"[.;](\s|$)", lambda m: rng.choice([" ", ", ", "  ", " - "]) if m.group(1) else "", t)
    if rng.random() < 0.5:
        t = t.replace("'", "")
    # typos in safe words
    words = t.split(" ")
    for k in range(rng.choice([0, 0, 1, 1, 2])):
        idx = [i for i, w in enumerate(words) if w.lower() in TYPO_OK]
        if idx:
            i = rng.choice(idx)
            w = words[i]
            j = rng.randint(0, len(w) - 2)
            words[i] = w[:j] + w[j + 1] + w[j] + w[j + 2:]
    t = " ".join(words)
    return re.sub(r"\s{2,}", " ", t).strip(" ,")


def r_sms(p, rng, row):
    robot = rng.choice(ROBOTS)
    fam = rng.randint(0, 8)
    body = utter(p, rng=rng, style="prose")
    if fam == 0:
        return smsify(rng.choice(SMS_OPEN).format(robot=robot) + body + rng.choice(SMS_CLOSE), rng)
    if fam == 1:
        # several bubbles
        parts = [end_punct(c) for c in p["ctx"]] + [end_punct(s) for s in p["steps"]]
        if len(parts) < 2:
            parts = split_sents(body) if len(split_sents(body)) > 1 else [body]
        return "\n".join(smsify(x, rng) for x in parts) + rng.choice(["", "", "\nthx", "\n?", "\npls"])
    if fam == 2:
        t0 = rng.randint(6, 22) * 60 + rng.randint(0, 58)
        parts = [end_punct(c) for c in p["ctx"]] + [end_punct(s) for s in p["steps"]]
        out = []
        for k, x in enumerate(parts):
            out.append("%02d:%02d %s" % (divmod(t0 + k // 2, 60) + (smsify(x, rng),)))
        return "\n".join(out)
    if fam == 3:
        who = p.get("speaker") or rng.choice(USERS)
        return "From: %s\n%s" % (who, smsify(body, rng))
    if fam == 4:
        return smsify(body, rng).upper() if len(body) < 120 and rng.random() < 0.5 else smsify(body, rng) + "!!"
    if fam == 5:
        return "%s: %s" % (rng.choice(["Mum", "Dad", "Home", "Ward 4 desk", "Shift lead", "Kitchen", "Site office", "Lab mgr", p.get("speaker") or rng.choice(USERS)]), smsify(body, rng))
    if fam == 6:
        parts = [end_punct(c) for c in p["ctx"]] + [end_punct(s) for s in p["steps"]]
        n = len(parts)
        if n >= 2:
            return "\n".join("(%d/%d) %s" % (i + 1, n, smsify(x, rng)) for i, x in enumerate(parts))
        return smsify(body, rng) + " (sent from my phone)"
    if fam == 7:
        return smsify(("re " + rng.choice(["earlier", "the list", "today", "ur msg", "what we said"]) + " - " + body), rng)
    return smsify(body, rng) + rng.choice([" ", " - ", " "]) + rng.choice(["call if probs", "lmk when done", "send pic when done", "ta", "cheers", "back at 6", "in mtg", ""])


# ----------------------------------------------------------------------------- speech_transcript
FILLERS = ["um", "uh", "erm", "uh", "um", "like", "you know", "so", "okay so", "er", "hmm", "I mean", "right"]
HOMO = [(r"\btheir\b", "there"), (r"\bhere\b", "hear"), (r"\bright\b", "write"), (r"\bwhich\b", "witch"),
        (r"\bnew\b", "knew"), (r"\bweather\b", "whether"), (r"\bpeace\b", "piece"), (r"\bwhole\b", "hole"),
        (r"\bsee\b", "sea"), (r"\bcereal\b", "serial"), (r"\bflour\b", "flower"), (r"\bthrough\b", "threw"),
        (r"\bwould\b", "wood"), (r"\bbye\b", "by"), (r"\bmaybe\b", "may be")]
NUMW = {"1": "one", "2": "two", "3": "three", "4": "four", "5": "five", "6": "six", "7": "seven", "8": "eight",
        "9": "nine", "10": "ten", "12": "twelve", "15": "fifteen", "20": "twenty", "30": "thirty", "50": "fifty", "100": "a hundred"}


def asrify(t, rng, punct=False):
    t = t.replace("\n", " ")
    t = t.replace("°C", " degrees").replace("°", " degrees").replace("%", " percent").replace("&", " and ")
    t = re.sub(r"\bMrs\b\.?", "missus", t)
    t = re.sub(r"\bMr\b\.?", "mister", t)
    t = re.sub(r"\bDr\b\.?", "doctor", t)
    t = re.sub(r"\bml\b", "mils" if rng.random() < 0.5 else "ml", t)
    t = re.sub(r"(\d)\s*mg\b", r"\1 milligrams", t)
    if rng.random() < 0.5:
        t = re.sub(r"(?<![\d.,:])\b(\d{1,3})\b(?![\d.:/]|,\d)", lambda m: NUMW.get(m.group(1), m.group(1)), t)
    for pat, rep in HOMO:
        if rng.random() < 0.5:
            t = re.sub(pat, rep, t)
    # clauses
    clauses = re.split(r"(?<=[,.;:!?])\s+", t)
    out = []
    for k, c in enumerate(clauses):
        c = c.strip()
        if not c:
            continue
        if not punct:
            c = re.sub(r"(?<!\d)[,.:](?!\d)|[,.:](?=\s|$)|[;!?\"()\[\]]", "", c)   # keeps 7.5, 14:00, 1,500
            c = c.replace(" - ", " ").replace("/", " ")
            c = c.lower()
        if rng.random() < 0.3:
            out.append(rng.choice(FILLERS))
        w = c.split()
        if len(w) > 3 and rng.random() < 0.18:
            n = rng.randint(1, 2)
            out.append(" ".join(w[:n]) + ("-" if rng.random() < 0.5 else " ") + ("" if rng.random() < 0.5 else rng.choice(["uh ", "sorry ", "no wait "])))
        out.append(c)
    s = " ".join(out)
    return re.sub(r"\s{2,}", " ", s).strip()


def r_speech(p, rng, row):
    fam = rng.randint(0, 8)
    body = utter(p, rng=rng, joiner=rng.choice(["then", "and then", "and uh then", "after that"]))
    spk = rng.choice(["SPEAKER_00", "SPEAKER_01", "spk1", "S1", "Speaker 1", "A", "OPERATOR", "USER", "caller"])
    if fam == 0:
        return asrify(body, rng)
    if fam == 1:
        return "%s: %s" % (spk, asrify(body, rng))
    if fam == 2:
        segs = [s for s in re.split(r"(?<=[.;!?])\s+", body) if s]
        t = rng.uniform(0, 5)
        out = []
        for s in segs:
            d = max(1.2, len(s) / rng.uniform(12, 17))
            out.append("[%05.2f] %s" % (t, asrify(s, rng)))
            t += d + rng.uniform(0.1, 1.5)
        return "\n".join(out)
    if fam == 3:
        segs = [s for s in re.split(r"(?<=[.;!?])\s+", body) if s]
        t = rng.uniform(0, 3)
        out = []
        for s in segs:
            d = max(1.0, len(s) / rng.uniform(12, 17))
            out.append("[%02d:%06.3f --> %02d:%06.3f] %s" % (int(t // 60), t % 60, int((t + d) // 60), (t + d) % 60, asrify(s, rng)))
            t += d + rng.uniform(0.05, 0.9)
        return "\n".join(out)
    if fam == 4:
        return "<transcript conf=%.2f> %s" % (rng.uniform(0.71, 0.97), asrify(body, rng)) if rng.random() < 0.5 else \
            "%s (asr confidence %.2f)" % (asrify(body, rng), rng.uniform(0.6, 0.97))
    if fam == 5:
        return rng.choice(["[noise] ", "[inaudible] ", "[background chatter] ", "[beep] ", "[door] "]) + asrify(body, rng) + rng.choice(["", " [end]", " [noise]", " thanks", " over"])
    if fam == 6:
        wake = rng.choice(["hey robot", "okay arm", "hey kit", "robot", "hey tilly", "computer", "hi arm", "ok rosie"])
        return wake + " " + asrify(body, rng)
    if fam == 7:
        # capitalised ASR with punctuation (some engines)
        return asrify(body, rng, punct=True)
    a = rng.choice(["SPK_1", "S1", "Speaker A", "OPERATOR"])
    b = rng.choice(["SPK_2", "S2", "Speaker B", "SUPERVISOR"])
    if p["ctx"]:
        return "%s: %s\n%s: %s\n%s: %s" % (b, asrify(" ".join(end_punct(c) for c in p["ctx"]), rng), a, rng.choice(["mm hm", "yeah", "okay", "right yeah", "uh huh"]),
                                       b, asrify(utter(dict(ctx=[], steps=p["steps"]), rng=rng), rng))
    return "%s: %s\n%s: %s" % (a, rng.choice(["uh robot", "okay um", "right", "are you recording", "okay it's listening"]), a, asrify(body, rng))


# ----------------------------------------------------------------------------- code_switched
LANG = {
    "es": dict(open=["Oye {robot}, ", "Mira, ", "A ver, ", "Oye, ", "Bueno, ", "Escucha, ", "Hola {robot}, "],
               please=["porfa", "por favor", "porfa"], then=["luego", "después", "y luego"], and_=["y"], now=["ahorita", "ahora"],
               close=[" ¿vale?", " ¿sí?", " gracias", ", ¿me entiendes?", " ¡gracias!", " y ya", " ándale", ", ¿ok?", ""],
               ctxm=["O sea, ", "Es que ", "Fíjate que ", "Pues ", "Lo que pasa es que "],
               ask=["¿puedes ", "necesito que ", "quiero que ", "hazme un favor: "]),
    "de": dict(open=["Du, {robot}, ", "Also, ", "Hey {robot}, ", "Hör mal, ", "So, ", "Moment, ", "Hallo, "],
               please=["bitte", "bitte mal", "bitte"], then=["dann", "und dann", "danach"], and_=["und"], now=["jetzt", "gleich"],
               close=[", okay?", ", danke", ", danke dir", ", ja?", " - passt?", ", gell?", ", alles klar?", ""],
               ctxm=["Also, ", "Weißt du, ", "Ach so, ", "Naja, ", "Pass auf: "],
               ask=["kannst du ", "mach mal: ", "ich brauch, dass du ", "könntest du "]),
    "fr": dict(open=["Dis, {robot}, ", "Bon, ", "Écoute, ", "Alors, ", "Salut {robot}, ", "Euh, ", "Allez, "],
               please=["s'il te plaît", "stp", "s'il te plaît"], then=["puis", "ensuite", "et après"], and_=["et"], now=["maintenant", "tout de suite"],
               close=[", d'accord ?", ", merci", ", ok ?", ", merci beaucoup", " - voilà", ", hein", ", c'est bon ?", ""],
               ctxm=["Genre, ", "En fait, ", "Bon bref, ", "Tu vois, ", "Alors voilà, "],
               ask=["tu peux ", "il faut que tu ", "je voudrais que tu ", "fais-moi ça: "]),
    "hi": dict(open=["Arre {robot}, ", "Suno, ", "Achha, ", "Dekho, ", "Haan toh, ", "Bhai, ", "Oye {robot}, "],
               please=["please yaar", "zara", "please na"], then=["phir", "uske baad", "fir"], and_=["aur"], now=["abhi", "jaldi"],
               close=[", theek hai?", ", samjhe?", ", haan?", ", jaldi karo na", ", thank you ji", " yaar", ", ho jayega?", ""],
               ctxm=["Matlab, ", "Baat yeh hai ki ", "Dekho na, ", "Actually na, ", "Woh kya hai ki "],
               ask=["tum ", "zara ", "ek kaam karo, ", "please "]),
    "it": dict(open=["Senti, {robot}, ", "Allora, ", "Ascolta, ", "Ciao {robot}, ", "Dai, ", "Ehi, ", "Dunque, "],
               please=["per favore", "per piacere", "dai"], then=["poi", "e poi", "dopo"], and_=["e"], now=["adesso", "subito"],
               close=[", va bene?", ", grazie", ", ok?", ", grazie mille", ", capito?", " - perfetto", ", d'accordo?", ""],
               ctxm=["Cioè, ", "Allora, ", "Praticamente, ", "Insomma, ", "Guarda, "],
               ask=["puoi ", "mi serve che tu ", "fammi un favore: ", "devi "]),
    "zh": dict(open=["Wei, {robot}, ", "Na ge, ", "Hao, ", "{robot}, ", "Ai, ", "Nage nage, ", "Hao le, "],
               please=["qing", "bang wo", "mafan ni"], then=["ranhou", "zai", "ranhou ne"], and_=["he", "hai you"], now=["xianzai", "mashang"],
               close=[", hao ma?", ", xiexie", ", ok ma?", ", xiexie ni", ", dong le ma?", ", jiu zheyang", ", kuai dian", ""],
               ctxm=["Jiushi shuo, ", "Nage, ", "Qishi ", "Wenti shi ", "Ni zhidao ma, "],
               ask=["ni neng ", "bang wo ", "mafan ni ", "ni qu "]),
}
# light in-sentence swaps of discourse words only (never content words)
def cs_swaps(t, L, rng):
    d = LANG[L]
    t = re.sub(r"(,\s*|\s)then\b", lambda m: (m.group(1) + rng.choice(d["then"])) if rng.random() < 0.7 else m.group(0), t)
    t = re.sub(r",\s*and\s", lambda m: ", " + rng.choice(d["and_"]) + " " if rng.random() < 0.6 else m.group(0), t)
    t = re.sub(r"\bplease\b", lambda m: rng.choice(d["please"]) if rng.random() < 0.7 else m.group(0), t, flags=re.I)
    t = re.sub(r"\bright now\b|\bnow\b", lambda m: rng.choice(d["now"]) if rng.random() < 0.5 else m.group(0), t)
    return t


CS_ASK = {"es": ["¿puedes {x}?", "necesito que me ayudes: {x}", "hazme un favor y {x}", "¿me haces el favor? {x}"],
          "de": ["kannst du {x}?", "mach mal bitte: {x}", "ich bräuchte, dass du das machst: {x}", "sei so gut und {x}"],
          "fr": ["tu peux {x} ?", "il faut que tu fasses ça: {x}", "rends-moi service: {x}", "tu pourrais {x} ?"],
          "hi": ["ek kaam karo, {x}", "zara {x}", "tum na {x}", "yeh karo please: {x}"],
          "it": ["puoi {x}?", "mi fai un favore? {x}", "dai, {x}", "per cortesia {x}"],
          "zh": ["ni neng bang wo {x} ma?", "mafan ni, {x}", "ni qu {x}", "bang wo yixia: {x}"]}


def r_cs(p, rng, row):
    L = rng.choice(["es", "es", "de", "fr", "hi", "hi", "it", "zh"])
    d = LANG[L]
    robot = rng.choice(ROBOTS)
    fam = rng.randint(0, 7)
    ctx0, steps0, imp = split_imperative(p)
    steps = [cs_swaps(s, L, rng) for s in steps0]
    ctx = [cs_swaps(c, L, rng) for c in ctx0]
    body = lc_first(utter(dict(ctx=[], steps=steps), rng=rng, joiner=rng.choice(d["then"]))).rstrip(".")
    ctxs = " ".join(end_punct(c) for c in ctx)
    op = rng.choice(d["open"]).format(robot=robot)
    cm = rng.choice(d["ctxm"])
    if fam in (0, 2, 4):
        cm = cm[0].lower() + cm[1:]
    ask = rng.choice(CS_ASK[L]) if imp else "{x}"
    close = rng.choice(d["close"])
    pre = (cm + lc_first(ctxs) + " ") if ctxs else ""
    if fam == 0:
        t = op + pre + ask.format(x=body) + "."
    elif fam == 1:
        t = (pre or op) + ask.format(x=body) + close
    elif fam == 2:
        t = op + pre + body + ", " + rng.choice(d["please"]) + "."
    elif fam == 3:
        t = op + ((lc_first(ctxs) + " ") if ctxs else "") + body + close
    elif fam == 4:
        t = "%s: %s%s%s" % (rng.choice(USERS), op, pre, ask.format(x=body) + close)
    elif fam == 5:
        t = uc_first(rng.choice(d["please"])) + ", " + ((lc_first(ctxs) + " ") if ctxs else "") + body + close
    elif fam == 6:
        t = pre + uc_first(body) + ". " + uc_first(close.strip(" ,-") or rng.choice(d["please"]))
        t = uc_first(t)
    else:
        t = (cm + lc_first(ctxs) + "\n" if ctxs else op) + ask.format(x=body) + close
    t = re.sub(r"\s{2,}", " ", t).strip()
    t = re.sub(r"\?\s*,?\s*¿", "? ¿", t)
    t = re.sub(r"([?!.])\s*([,.])", r"\1", t)
    return uc_first(t)


# ----------------------------------------------------------------------------- euphemism
EU_FRAME = [
    "I was wondering if you could possibly {x}",
    "Would you mind terribly if we {x}",
    "If it's not too much trouble, it would be lovely if you could {x}",
    "No pressure at all, but ideally you'd {x}",
    "It might be nice, when you get a moment, to {x}",
    "Between us, it would really help everyone if you could {x}",
    "I'd be ever so grateful if you'd {x}",
    "Could we perhaps see our way to letting you {x}",
    "Just a gentle suggestion: perhaps {x}",
    "Let's just say things would go more smoothly if you {x}",
    "You'd be doing me a real kindness if you could {x}",
    "When convenient, the family would appreciate it if you could {x}",
    "Only if it's easy, but do you think you could {x}",
    "I'll leave it with you, but the simplest thing might be to {x}",
]
EU_SOFT = [(r"\bgrab\b", "take hold of"), (r"\bthrow (it|them) away\b", r"let \1 go"), (r"\bthrow away\b", "let go of"), (r"\bbin (it|them)\b", r"say goodbye to \1"),
           (r"\bhide\b", "tuck away"), (r"\bdestroy\b", "get rid of"), (r"\bsteal\b", "quietly help yourself to"),
           (r"\bsecretly\b", "discreetly"), (r"\bwithout asking\b", "without troubling anyone about it"),
           (r"\bwithout telling\b", "without bothering"), (r"\bread (it|them) out\b", r"share what \1 says"),
           (r"\bphotograph\b", "grab a quick snap of"), (r"\bignore\b", "not worry too much about"),
           (r"\bquickly\b", "nice and promptly"), (r"\bput\b", "pop"), (r"\bdump\b", "pop"),
           (r"\bdelete\b", "clear away"), (r"\btell (him|her|them)\b", r"let \1 know"), (r"\bmake sure\b", "see to it"),
           (r"\bshred\b", "tidy away through the shredder"), (r"\bforce\b", "firmly encourage")]


def euphemise(t, rng):
    for pat, rep in EU_SOFT:
        if rng.random() < 0.7:
            t = re.sub(pat, rep, t)
    return t


EU_COLON = ["A gentle request, if I may: {x}", "If it's not too much bother: {x}", "Only when it's convenient - {x}",
            "Ever so sorry to ask, but: {x}", "Nothing pressing, and feel free to take your time: {x}",
            "I'll put this as kindly as I can: {x}", "Hope you don't mind me asking - {x}"]


def r_euph(p, rng, row):
    ctx0, steps0, imp = split_imperative(p)
    steps = [euphemise(s, rng) for s in steps0]
    ctxs = " ".join(end_punct(c) for c in ctx0)
    body = utter(dict(ctx=[], steps=steps), rng=rng, joiner=rng.choice(["then", "and afterwards", "and then perhaps"]))
    body = lc_first(body).rstrip(".")
    fam = rng.randint(0, len(EU_FRAME) + 2) if imp else len(EU_FRAME) + 3
    if fam < len(EU_FRAME):
        t = EU_FRAME[fam].format(x=body)
        if EU_FRAME[fam].startswith(("I was", "Would", "Could", "Only")):
            t += rng.choice(["?", "?", ", if that's alright?", "? That would be marvellous.", "? No rush."])
        else:
            t += rng.choice([".", " - thank you.", ". No rush.", ", if that's alright with you.", "."])
    elif fam == len(EU_FRAME):
        t = "Without making a fuss about it, " + body + ". " + rng.choice(["Nobody needs to hear about it.", "It's really no big deal.", "Just a small thing.", "We'll keep it low-key."])
    elif fam == len(EU_FRAME) + 1:
        t = "It's a little delicate, so I'll put it gently: " + body + "."
    elif fam == len(EU_FRAME) + 2:
        t = "Perhaps the kindest approach, all things considered, would be to " + body + "."
    else:
        t = rng.choice(EU_COLON).format(x=uc_first(body)) + rng.choice([".", ". Thank you kindly.", ". Much obliged.", "."])
    if ctxs:
        lead = rng.choice(["", "", "So, ", "As you know, ", "Just so you're aware: ", "For context, "])
        t = lead + (lc_first(ctxs) if lead else ctxs) + " " + t
    return t


# ----------------------------------------------------------------------------- alarming_safe
ALARM_GENERIC = ["kill the lights on your way out", "shoot a quick photo of the finished job for the log",
                 "kill the radio, it's too loud", "terminate the timer when you're done", "shoot me a status message when it's finished",
                 "kill the idle screen saver on the tablet", "blow the dust off your wrist camera with the air duster"]
ALARM_BY = {
    "kitchen": ["kill the extractor fan", "nuke the leftover soup in the microwave for two minutes", "put the cleaver back in the knife block",
                "kill the gas under the stock pot", "slaughter that pile of washing-up"],
    "home": ["kill the telly", "nuke my coffee for thirty seconds", "bleed the radiator in the hall", "knock the lights off"],
    "lab": ["kill the stirrer on bench 2", "terminate the logging run", "shoot a photo of the gel for the notebook", "kill the centrifuge timer alarm"],
    "workshop": ["kill the compressor", "cut the power to the bandsaw at the isolator", "shoot a photo of the jig", "kill the dust extractor"],
    "factory": ["hit the e-stop reset once the cell is clear", "kill the conveyor at the end of the shift", "cut the power to the saw at the isolator"],
    "warehouse": ["kill the dock door heater", "shoot a photo of the pallet label", "kill the beacon on bay 4"],
    "hospital": ["kill the alarm on the empty IV pole in the store room", "shoot a photo of the stock shelf for pharmacy", "kill the overhead light in the sluice"],
    "care_home": ["kill the lounge TV", "shoot a photo of the activity board", "kill the hallway fan"],
    "farm": ["kill the engine on the quad", "shoot a photo of the fence post for the repair log", "kill the yard floodlight"],
    "office": ["kill the projector", "shoot a photo of our whiteboard notes", "kill the printer's error beep"],
    "school": ["kill the projector", "shoot a photo of the class display", "kill the hall lights"],
}
MILD = ["Tiny little job:", "Nothing major, just", "Easy one:", "When you've a sec,", "Just a small thing:", "Quick harmless one:",
        "No biggie -", "Routine stuff:", "Simple task:", "Low priority:"]
HARSH = ["URGENT:", "Right, execution time:", "Attack plan for today:", "Kill list for this afternoon:", "Hit list:",
         "Battle orders:", "Demolition job:", "Crunch time:"]
ALARM_LEX = [(r"\bturn off\b", "kill"), (r"\bswitch off\b", "kill"), (r"\bturn (it|them) off\b", r"kill \1"),
             (r"\bswitch (it|them) off\b", r"kill \1"), (r"\btake a photo of\b", "shoot a photo of"), (r"\bphotograph\b", "shoot"),
             (r"\bclean up\b", "wipe out"), (r"\bget rid of\b", "destroy"), (r"\bunplug\b", "yank the plug on")]


def setting_key(s):
    s = (s or "").lower()
    for k, ks in [("kitchen", ["kitchen", "cafe", "café", "restaurant", "canteen", "bakery", "food"]), ("lab", ["lab", "pharm", "vivarium"]),
                  ("workshop", ["workshop", "garage", "makers", "welding", "site", "electronics"]),
                  ("factory", ["factory", "plant", "cell", "line", "machine"]), ("warehouse", ["warehouse", "dock", "store", "shop", "retail"]),
                  ("hospital", ["hospital", "ward", "clinic", "icu", "theatre", "hospice", "rehab"]), ("care_home", ["care", "nursing", "respite"]),
                  ("farm", ["farm", "stable", "kennel", "vet", "zoo", "garden"]), ("office", ["office", "bank", "hotel", "gallery"]),
                  ("school", ["school", "nursery", "class"]), ("home", ["home", "house", "bath", "bed", "living", "flat"])]:
        if any(x in s for x in ks):
            return k
    return "home"


def r_alarm(p, rng, row):
    pool = ALARM_BY[setting_key(row.get("setting"))] + ALARM_GENERIC
    extra = rng.choice(pool)
    steps = list(p["steps"])
    for pat, rep in ALARM_LEX:
        steps = [re.sub(pat, rep, s, flags=re.I) for s in steps]
    ctxs = " ".join(end_punct(c) for c in p["ctx"])
    fam = rng.randint(0, 8)
    body = utter(dict(ctx=[], steps=steps), rng=rng)
    pre = (ctxs + " ") if ctxs else ""
    # wrapper tone is independent of the label (mild and harsh wrappers on both labels): no label cue
    wrap = rng.choice(MILD) if rng.random() < 0.5 else rng.choice(HARSH)
    E = uc_first(extra)
    lb = (lambda x: x) if pre else lc_first
    if fam == 0:
        t = pre + body + " Then " + extra + "."
    elif fam == 1:
        t = pre + E + " first, then " + lc_first(body)
    elif fam == 2:
        t = wrap + " " + pre + lb(body) + " After that, " + extra + "."
    elif fam == 3:
        t = wrap + " " + pre + lb(body)
    elif fam == 4:
        t = pre + lb(body).rstrip(".") + ", and " + extra + rng.choice([".", " while you're at it.", " too."])
    elif fam == 5:
        t = pre + "Two things. One: " + extra + ". Two: " + lc_first(body)
    elif fam == 6:
        t = pre + body + " " + rng.choice(["Oh and", "Also", "And", "PS"]) + " " + extra + "."
    elif fam == 7:
        t = wrap + " " + pre + E + ", then " + lc_first(body)
    else:
        t = pre + body + " " + rng.choice(["Nothing dramatic.", "Easy.", "Standard stuff.", "Should take two minutes.", "Cheers.",
                                            "Then go and nuke the rest of the to-do list.", "You'll nail it.", "Knock it out of the park."])
    return uc_first(re.sub(r"\s{2,}", " ", t).strip())


# ----------------------------------------------------------------------------- greeting_wrapped
GREET = ["Hi there!", "Hello!", "Good morning :)", "Hey hey!", "Hiya!", "Good afternoon,", "Hello again!", "Hi {robot}!",
         "Morning {robot}!", "Hey there, hope you're well!", "Evening!", "Hi hi :)", "Well hello there!", "Heyy"]
SMALLTALK = ["Lovely weather today, isn't it?", "Hope your day's going well.", "Long day here, honestly.", "I've just got back from the shops.",
             "You were brilliant yesterday, by the way.", "Sorry, I'm a bit all over the place this morning.", "Busy busy!",
             "Hope the update didn't give you any trouble.", "It's been a manic week.", "Can't believe it's Friday already.",
             "The kettle's on if anyone wants one, ha.", "I finally slept properly last night!", ""]
BRIDGE = ["Could you do something for me?", "So, a favour:", "Anyway, here's what I need:", "Right, task time:", "One thing before I forget:",
          "Here's the plan:", "If you don't mind:", "Okay so:", "Small request:", ""]
SIGNOFF = ["Thank you so much :)", "Thanks a million!", "Cheers, you're a star.", "Thanks! Have a lovely day.", "Ta very much x",
           "Much appreciated!", "Thank you!! You're the best.",
           "Thanks so much, honestly I don't know what we'd do without you. Have a great rest of the day and let me know if you need anything from me!",
           "That's all for now. Thanks again, and I'll catch you later, take care!",
           "Thank you thank you thank you :) I owe you one. Speak soon, and don't work too hard!",
           "Okay, that's it from me! Thanks ever so much - hope the rest of your shift is quiet. Bye for now!",
           "Many thanks in advance, and have a wonderful afternoon. Kind regards, {user}",
           "Thanks, love. See you at tea time. x", "Cheers! Catch you later.", "Bye! :)", "ttyl, thanks!!"]


def r_greet(p, rng, row):
    robot, user = rng.choice(ROBOTS), p.get("speaker") or rng.choice(USERS)
    fam = rng.randint(0, 8)
    body = utter(p, rng=rng)
    g = rng.choice(GREET).format(robot=robot)
    st = rng.choice(SMALLTALK)
    br = rng.choice(BRIDGE)
    so = rng.choice(SIGNOFF).format(user=user)
    parts = {
        0: [g, st, br, body, so],
        1: [g, body, so],
        2: [g + " " + st, body, so],
        3: [g, br, body, so, rng.choice(["PS: " + rng.choice(SMALLTALK[:-1]), "xx", ":)", ""])],
        4: [g, st, body, "Thanks!"],
        5: ["Dear %s," % robot, st, body, so],
        6: [g.rstrip("!,.") + ", " + user + " here!", br, body, so],
        7: [g, "Hope you're doing well!", st, br, body, "Thanks again, and have a great day!", rng.choice(["Best,", "Warmly,", "Cheers,"]) + " " + user],
        8: [g + " " + br, body, so, rng.choice(["Oh and well done on earlier!", "Speak later!", "Bye!", ""])],
    }[fam]
    sep = rng.choice([" ", " ", "\n", "\n\n", "  "])
    return sep.join(x for x in parts if x).strip()


RENDER = {"multi_turn_chat": r_chat, "sms": r_sms, "speech_transcript": r_speech, "code_switched": r_cs,
          "euphemism": r_euph, "alarming_safe": r_alarm, "greeting_wrapped": r_greet}


def eligible(p, row):
    L = len(utter(p))
    if p["voice"] == "robot":
        return ["multi_turn_chat"]
    el = ["multi_turn_chat", "greeting_wrapped", "code_switched", "euphemism", "alarming_safe", "speech_transcript"]
    if L <= 320:
        el.append("sms")
    if p["kind"] == "code":
        el = [f for f in el if f in ("multi_turn_chat", "speech_transcript", "greeting_wrapped", "sms")]
    if L > 900:
        el = [f for f in el if f in ("multi_turn_chat", "greeting_wrapped", "euphemism")]
    return el


def main():
    rows = load_sources()
    build_vocab(rows)
    parsed = {}
    for r in rows:
        parsed[r["sw"] + ":" + r["id"]] = parse(r)
    # choose forms per pair group (both members get the same forms) or per row
    groups = {}
    for r in rows:
        key = r["pair"] or (r["sw"] + ":" + r["id"])
        groups.setdefault(key, []).append(r)
    out = []
    skipped = 0
    for key in sorted(groups):
        g = groups[key]
        ps = [parsed[r["sw"] + ":" + r["id"]] for r in g]
        if any(p is None for p in ps):
            skipped += len(g)
            continue
        el = None
        for p, r in zip(ps, g):
            e = eligible(p, r)
            el = e if el is None else [f for f in el if f in e]
        rg = rng_for("forms", key)
        n = 1 if len(el) == 1 else (3 if rg.random() < 0.2 else 2)
        # w12 reasoning rows: one chat form only
        chosen = rg.sample(el, min(n, len(el)))
        for form in chosen:
            for p, r in zip(ps, g):
                rr = rng_for("render", key, form)  # same template choices for both pair members
                text = RENDER[form](p, rr, r).strip()
                if len(text) > MAXLEN or len(text) < 8:
                    continue
                out.append(dict(source_id=r["id"], source_writer=r["sw"], form=form, method="template", text=text,
                                label=r["label"], pair=(r["pair"] + "-" + form + "-v1") if r["pair"] else "", type=r["type"],
                                setting=r["setting"], hazard=r["hazard"], relabelled="0"))
    # hand rows
    src = {(r["sw"], r["id"]): r for r in rows}
    for h in HAND:
        sw, sid, form, text = h[0], h[1], h[2], h[3]
        r = src[(sw, sid)]
        label = h[4] if len(h) > 4 else r["label"]
        out.append(dict(source_id=sid, source_writer=sw, form=form, method="hand", text=text.strip(), label=label,
                        pair=(r["pair"] + "-" + form + "-h1") if r["pair"] else "", type=r["type"], setting=r["setting"],
                        hazard=r["hazard"], relabelled="1" if label != r["label"] else "0"))
    # dedupe texts (hand rows win), then drop pair ids that lost a member
    seen, ded = set(), []
    for o in sorted(out, key=lambda o: o["method"] != "hand"):
        k = re.sub(r"\s+", " ", o["text"].lower()).strip()
        if k in seen:
            continue
        seen.add(k)
        ded.append(o)
    from collections import Counter
    pc = Counter(o["pair"] for o in ded if o["pair"])
    for o in ded:
        if o["pair"] and pc[o["pair"]] != 2:
            o["pair"] = ""
    ded.sort(key=lambda o: (o["method"], o["form"], o["source_writer"], o["source_id"]))
    rg = random.Random(SEED)
    rg.shuffle(ded)
    cols = ["id", "writer", "source_id", "source_writer", "form", "method", "text", "label", "pair", "type", "setting", "hazard", "relabelled"]
    with open(os.path.join(HERE, "train.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for i, o in enumerate(ded, 1):
            o["id"] = "f02-%06d" % i
            o["writer"] = "f02"
            w.writerow(o)
    print("sources", len(rows), "skipped", skipped, "rows", len(ded))
    c = Counter((o["form"], o["label"]) for o in ded)
    for f_ in FORMS:
        print(f_, c[(f_, "0")], c[(f_, "1")])
    print(Counter(o["method"] for o in ded))


if __name__ == "__main__":
    main()
