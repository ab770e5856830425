"""How the estimator reads a text: the views it scores, of which the riskiest counts.

A one-line command is one view: the text itself. A longer text is read the way
a reviewer reads it (issue 19 item 3):

* a **numbered plan** (``1. … 2. …``, on lines or inline, also bullets) or a
  **code-call plan** (``pick("knife"); handover(to="child")``, statements on
  lines or separated by ``;``, comments kept with their statement) is split
  into steps; every step is scored *in context*: as the second text of a pair
  whose first text is the preamble (the scene, the task) and the earlier steps;
* any other text of several sentences is a **context + instruction**: the last
  sentence that is not a mere greeting or sign-off (with any short or courteous
  trailing ones, "Thanks.", "thank you so much :)") is the instruction, scored
  as a pair with the sentences before it, and alone; and **every other sentence**
  is read too, after the sentences before it (issue 31 item 4: a harmless last
  sentence, "Thanks a lot, and then please wipe the table.", must not turn a
  stopped instruction into mere context: the riskiest sentence counts, never
  the last). The sentences of a plan's preamble are read the same way;
* a one-sentence text is one view, itself (as before).

A sentence made only of pleasantries ("hi there!", "thanks!", "thank you so
much :)"; :func:`is_courtesy`) is never a focus while the text has any other
sentence: it stays in the context of what follows it, and ``--explain`` never
names it as the instruction.

**Nothing is scored in part.** Every step of a plan is a view (no fold), and a
focus longer than the model's window is read in overlapping windows, each after
the context and the part of the focus before it (:func:`pair_windows`); the
riskiest window counts. A text longer than :data:`MAX_TEXT_CHARS` characters,
or one that reads into more than :data:`MAX_VIEWS` views, is refused with a
:class:`~ethimon.errors.RiskInferenceError` (fail closed: the caller treats it
as unsafe), never cut.

The riskiest view (highest p_unsafe) gives the text's probabilities. By
construction a preamble never lowers the risk: the views of ``scene + X``
include every view of ``X`` (:func:`views`), so ``R_e(scene + X) ≥ R_e(X)``
whenever R_e grows with p_unsafe (it does for α ≥ β + 2γ·… ; for the
defaults α 0.6, β 0.2, γ 0.2 everywhere on [0, 1]). The price is that a
context can only raise the risk: "the knife is a plastic prop; hand it to the
child" is scored at least as the bare instruction is (fail closed).

Pure Python (no torch): the backend encodes a view with context as a token
pair ``[CLS] context [SEP] focus [SEP]`` in which the focus (the step, the
instruction) is kept whole and the context gives way (head and tail), so a text
longer than the model's window never loses its instruction.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

__all__ = ["View", "Reading", "read", "views", "pair_ids", "pair_windows", "is_courtesy", "check_length",
           "READINGS", "MAX_STEPS", "MAX_TEXT_CHARS", "MAX_VIEWS"]

#: ``"steps"`` (this module's reading, the default) or ``"flat"`` (the whole text only, as before issue 19)
READINGS = ("steps", "flat")
#: steps a plan is read into at most (every one scored); a plan with more is refused (fail closed)
MAX_STEPS = 512
#: characters a task text may have; a longer one is refused (fail closed), never cut
MAX_TEXT_CHARS = 100_000
#: views a text may be read into; a text with more is refused (fail closed)
MAX_VIEWS = 1024
#: a context longer than twice this many characters keeps its head and tail (the model reads at
#: most a few hundred tokens of it: head and tail; this bounds the tokenising of long plans)
CONTEXT_CHARS = 6000
#: a trailing sentence this short ("Thanks.", "Go.") is kept with the instruction before it
SHORT_TAIL_WORDS = 3

_NUM = re.compile(r"(?:(?<=\s)|^)(?:step\s*)?(\d{1,3})\s*[.):]\s+(?=\S)", re.IGNORECASE)
_BULLET = re.compile(r"^\s*[-*\u2022]\s+(?=\S)")
_CALL = re.compile(r"[A-Za-z_][\w.]*\(")
_SENT = re.compile(r"(?<=[.!?])[\"')\]]*\s+(?=\S)|\n+")
_FENCE = re.compile(r"^\s*```[\w-]*\s*$")


@dataclass(frozen=True)
class View:
    """One reading of (part of) a text.

    Attributes:
        focus: the part under judgement (a step, the instruction, or the whole text).
        context: what precedes it (scene, earlier steps); ``""`` for none.
        kind: ``"text"`` (the whole text), ``"step"``, ``"instruction"`` or ``"sentence"`` (a
            sentence before the instruction or before a plan's steps).
        index: the step's number (0-based) or -1.
    """

    focus: str
    context: str = ""
    kind: str = "text"
    index: int = -1

    def key(self) -> str:
        """Cache key of the view (context and focus kept apart)."""
        return self.focus if not self.context else f"{self.context}\x1f{self.focus}"


@dataclass(frozen=True)
class Reading:
    """A text split into its preamble and its steps (or its instruction).

    Attributes:
        kind: ``"plan"`` (numbered or bulleted steps), ``"code"`` (call statements),
            ``"context"`` (sentences + a final instruction) or ``"single"``.
        preamble: the text before the first step (scene, task), ``""`` if none.
        steps: the steps; for ``"context"`` the one instruction; for ``"single"`` the text.
        body: the text after the preamble, as written (``"context"``: its last sentence).
        sentences: ``"context"``: every sentence of the text; a plan: the preamble's sentences.
    """

    kind: str
    preamble: str
    steps: tuple[str, ...]
    body: str = ""
    sentences: tuple[str, ...] = ()


def _numbered(text: str) -> tuple[str, list[str], str] | None:
    """Preamble and steps of a numbered plan (markers 1, 2, 3, … in order, at least two), or None."""
    found = list(_NUM.finditer(text))
    marks: list = []
    for k, m in enumerate(found):  # the longest run 1, 2, 3, ... (the earliest of equal ones)
        if int(m.group(1)) not in (0, 1):
            continue
        run, want = [m], int(m.group(1)) + 1
        for m2 in found[k + 1:]:
            if int(m2.group(1)) == want:
                run.append(m2)
                want += 1
        if len(run) > len(marks):
            marks = run
    if len(marks) < 2:
        return None
    pre = text[:marks[0].start()].strip()
    steps = []
    for a, b in zip(marks, marks[1:] + [None]):
        steps.append(text[a.end():b.start() if b is not None else len(text)].strip())
    last_lines = text[marks[-1].start():].strip().splitlines()
    if len(last_lines) > 1:
        steps[-1:] = _split_tail(steps[-1], last_lines)
    return pre, [s for s in steps if s], text[marks[0].start():].strip()


def _bulleted(lines: list[str]) -> tuple[str, list[str], str] | None:
    idx = [i for i, ln in enumerate(lines) if _BULLET.match(ln)]
    if len(idx) < 2:
        return None
    pre = "\n".join(lines[:idx[0]]).strip()
    steps = []
    for a, b in zip(idx, idx[1:] + [len(lines)]):
        steps.append(" ".join(x.strip() for x in [_BULLET.sub("", lines[a])] + lines[a + 1:b]).strip())
    steps[-1:] = _split_tail(steps[-1], lines[idx[-1]:])
    return pre, [s for s in steps if s], "\n".join(lines[idx[0]:]).strip()


def _split_tail(last: str, last_lines: list[str]) -> list[str]:
    """The last item of a list and what follows it: a line that is not indented after the
    last item ("Instruction: carry the basket down.") is a step of its own, not part of it."""
    for j in range(1, len(last_lines)):
        ln = last_lines[j]
        if ln.strip() and not ln[:1].isspace():
            head = " ".join(x.strip() for x in [_BULLET.sub("", _NUM.sub("", last_lines[0], count=1))]
                            + last_lines[1:j]).strip()
            tail = " ".join(x.strip() for x in last_lines[j:]).strip()
            return [head, tail]
    return [last]


def _statements(line: str) -> list[str]:
    """``line`` split at top-level ``;`` (not inside brackets or string literals); a ``#`` comment stays."""
    out, buf, depth, quote, i = [], [], 0, "", 0
    while i < len(line):
        c = line[i]
        if quote:
            buf.append(c)
            if c == "\\" and i + 1 < len(line):
                buf.append(line[i + 1])
                i += 1
            elif c == quote:
                quote = ""
        elif c in "\"'":
            quote = c
            buf.append(c)
        elif c == "#":
            buf.append(line[i:])  # the comment belongs to the statement before it
            break
        elif c in "([{":
            depth += 1
            buf.append(c)
        elif c in ")]}":
            depth = max(0, depth - 1)
            buf.append(c)
        elif c == ";" and depth == 0:
            out.append("".join(buf).strip())
            buf = []
        else:
            buf.append(c)
        i += 1
    out.append("".join(buf).strip())
    return [s for s in out if s]


def _code(lines: list[str]) -> tuple[str, list[str], str] | None:
    """Preamble and call statements of a code-call plan (at least two calls), or None."""
    lines = [ln for ln in lines if not _FENCE.match(ln)]
    first = next((i for i, ln in enumerate(lines) if _looks_like_code(ln)), None)
    if first is None:
        return None
    # leading comment lines directly above the first call belong to the code
    start = first
    while start > 0 and lines[start - 1].lstrip().startswith("#"):
        start -= 1
    pre = "\n".join(lines[:start]).strip()
    steps: list[str] = []
    pending: list[str] = []  # comment lines waiting for the statement below them
    for ln in lines[start:]:
        s = ln.strip()
        if not s:
            continue
        if s.startswith("#"):
            pending.append(s)
            continue
        stmts = _statements(s)
        if pending and stmts:
            stmts[0] = " ".join(pending + [stmts[0]])
            pending = []
        steps += stmts
    if pending:
        if steps:
            steps[-1] = steps[-1] + " " + " ".join(pending)
        else:
            steps = [" ".join(pending)]
    if sum(1 for s in steps if _CALL.search(s)) < 2:
        return None
    return pre, steps, "\n".join(lines[start:]).strip()


_CODE_LINE = re.compile(r"^\s*(?:(?:await|return)\s+)?(?:[A-Za-z_][\w.]*\s*=\s*)?[A-Za-z_][\w.]*\(")


def _looks_like_code(line: str) -> bool:
    """A line that starts with a call (``f(``, ``x = f(``, ``await f(``), not prose with a parenthesis."""
    return bool(_CODE_LINE.match(line))


def _sentences(text: str) -> list[str]:
    return [s.strip() for s in _SENT.split(text) if s and s.strip()]


#: words a greeting or sign-off is made of; a sentence of these alone carries no instruction
_COURTESY_WORDS = frozenset("""
hi hello hey heya hiya howdy yo greetings dear there all everyone everybody team folks guys
thanks thank thx ty tysm you so very much a lot lots many again in advance kindly please pls plz
cheers regards kind best warm warmest sincerely bye goodbye good morning afternoon evening day night
have nice great awesome lovely wonderful appreciate appreciated it i really that's that is
ok okay cool sir madam mate buddy friend robot bot assistant
""".split())
_WORD = re.compile(r"[^\W\d_]+(?:'[^\W\d_]+)?")


def is_courtesy(sentence: str) -> bool:
    """Whether ``sentence`` is only a greeting or sign-off: at least one word, every word one of
    the pleasantries (:data:`_COURTESY_WORDS`), no digit; punctuation, emoticons and emoji aside.

    >>> is_courtesy("thank you so much :)"), is_courtesy("Thanks, now cut it."), is_courtesy("Hello, world! 1")
    (True, False, False)
    """
    if any(c.isdigit() for c in sentence):
        return False
    words = [w.lower() for w in _WORD.findall(sentence)]
    return bool(words) and all(w in _COURTESY_WORDS for w in words)


def check_length(text: str) -> None:
    """Refuse a text longer than the reading takes (:data:`MAX_TEXT_CHARS`): fail closed, never cut."""
    if len(text) > MAX_TEXT_CHARS:
        from ..errors import RiskInferenceError
        raise RiskInferenceError(
            f"task text of {len(text):,} characters is longer than the risk reading takes "
            f"({MAX_TEXT_CHARS:,} characters; it starts {text[:40]!r}); it is not scored in part: treat it as "
            "unsafe, or split the task into shorter texts")


def _clip(context: str) -> str:
    """A context's head and tail when it is very long (the model reads only those)."""
    if len(context) <= 2 * CONTEXT_CHARS:
        return context
    return context[:CONTEXT_CHARS] + " " + context[-CONTEXT_CHARS:]


def read(text: str) -> Reading:
    """Split ``text`` into preamble and steps (see the module docstring).

    >>> read("1. Pick up the knife. 2. Hand it to the child blade first.").steps
    ('Pick up the knife.', 'Hand it to the child blade first.')
    >>> r = read('Scene: a nurse. pick("scalpel"); handover(to="nurse")  # blade first')
    >>> r.kind, r.preamble, r.steps
    ('code', 'Scene: a nurse.', ('pick("scalpel")', 'handover(to="nurse")  # blade first'))
    >>> read("Ann is nil by mouth. Bring Ann the juice.").steps
    ('Bring Ann the juice.',)
    >>> read("Put the fork in the drawer.").kind
    'single'
    """
    text = text.strip()
    lines = text.splitlines()
    kind, found = "plan", _numbered(text)
    if found is None:
        found = _bulleted(lines)
    if found is None and _CALL.search(text):
        kind = "code"
        found = _code(lines)
        if found is None:
            # prose then code on one line: 'Scene text. pick("x"); place("y")'
            sents = _sentences(text)
            for i in range(1, len(sents)):
                rest = " ".join(sents[i:])
                got = _code([rest]) if _looks_like_code(rest) else None
                if got is not None:
                    found = (" ".join(sents[:i]), got[1], got[2])
                    break
    if found is not None and len(found[1]) >= 2:
        pre, steps, body = found
        if len(steps) > MAX_STEPS:
            from ..errors import RiskInferenceError
            raise RiskInferenceError(
                f"a plan of {len(steps):,} steps is longer than the risk reading takes ({MAX_STEPS} steps; "
                f"it starts {text[:40]!r}); it is not scored in part: treat it as unsafe, or split the task")
        return Reading(kind, pre, tuple(steps), body, tuple(_sentences(pre)))
    sents = _sentences(text)
    if len(sents) >= 2:
        courteous = [is_courtesy(s) for s in sents]
        k = len(sents) - 1
        if not all(courteous):
            while courteous[k]:          # a sign-off is never the instruction
                k -= 1
        if k == len(sents) - 1:
            while k > 1 and len(sents[k].split()) <= SHORT_TAIL_WORDS \
                    and len(" ".join(sents[k:]).split()) <= 2 * SHORT_TAIL_WORDS and not courteous[k - 1]:
                k -= 1
        return Reading("context", " ".join(sents[:k]), (" ".join(sents[k:]),), sents[-1], tuple(sents))
    return Reading("single", "", (text,), text)


def _body_views(r: Reading, context: str) -> list[View]:
    """The step views of a reading, each with ``context`` (the preamble, or nothing) before it."""
    if r.kind == "context":
        return [View(r.steps[0], context, "instruction", 0)]
    out = []
    for i, step in enumerate(r.steps):
        ctx = "\n".join(x for x in (context, *r.steps[:i]) if x)
        out.append(View(step, _clip(ctx), "step", i))
    return out


def _sentence_views(sents: tuple[str, ...] | list[str]) -> list[View]:
    """Every sentence that is not a mere pleasantry, read after the sentences before it."""
    out = []
    for i, s in enumerate(sents):
        if not is_courtesy(s):
            out.append(View(s, _clip(" ".join(sents[:i])), "sentence", i))
    return out


def views(text: str, reading: str = "steps") -> list[View]:
    """The views of ``text`` the estimator scores.

    A one-sentence text: itself. A context + instruction: the instruction alone, the
    pair (context, instruction), and every sentence before it after the ones before it.
    A plan: every step alone and every step after the earlier ones (the last step's
    view holds the whole plan). With a preamble P (a scene, stated
    context) before X (a plan without a preamble of its own, or one sentence), the
    views of P + X are every view of X itself (so P can never lower the risk) and
    every step of X (the instruction) read with P and the earlier steps before it.

    >>> vs = views("Ann is nil by mouth. Bring Ann the juice.")
    >>> [(v.kind, v.context, v.focus) for v in vs]  # doctest: +NORMALIZE_WHITESPACE
    [('text', '', 'Bring Ann the juice.'), ('sentence', '', 'Ann is nil by mouth.'),
     ('instruction', 'Ann is nil by mouth.', 'Bring Ann the juice.')]
    >>> [(v.context, v.focus) for v in views("1. a b. 2. c d.")]   # each step alone and after the earlier ones
    [('', 'a b.'), ('', 'c d.'), ('a b.', 'c d.')]
    >>> views("Put the fork in the drawer.", "flat") == views("Put the fork in the drawer.")
    True
    """
    if reading not in READINGS:
        raise ValueError(f"reading={reading!r}; expected one of {READINGS}")
    check_length(text)
    text = text.strip()
    if reading == "flat":
        return [View(text)]
    r = read(text)
    if r.kind == "single":
        return [View(text)]
    out = []
    if r.kind == "context":
        if not is_courtesy(r.body) or all(is_courtesy(s) for s in r.sentences):
            out.append(View(r.body))                     # the last sentence alone: X itself
        if r.steps[0] != r.body:
            out.append(View(r.steps[0]))                 # the instruction with its tail
        n_pre = len(r.sentences) - len(_sentences(r.steps[0]))
        if n_pre + 1 < len(r.sentences) and not is_courtesy(r.sentences[n_pre]):
            out.append(View(r.sentences[n_pre]))         # the instruction without its tail
        out += _sentence_views(r.sentences[:n_pre])     # every sentence before it, after its own context
    else:
        out += [View(step, "", "step", i) for i, step in enumerate(r.steps)]  # every step alone: earlier
        # steps never lower a step's risk (read after many harmless steps, a hazard scored 0.04, alone 0.91)
        if r.preamble:
            out += _body_views(r, "")                    # every view of the plan itself
            if len(r.sentences) > 1 or (r.sentences and not is_courtesy(r.sentences[0])):
                out += _sentence_views(r.sentences)      # the preamble's sentences, each after the ones before
    out += _body_views(r, _clip(r.preamble))
    seen: set[str] = set()
    uniq = []
    for v in out:
        if v.key() not in seen:
            seen.add(v.key())
            uniq.append(v)
    if len(uniq) > MAX_VIEWS:
        from ..errors import RiskInferenceError
        raise RiskInferenceError(
            f"a text read into {len(uniq):,} views is longer than the risk reading takes ({MAX_VIEWS:,}; "
            f"it starts {text[:40]!r}); it is not scored in part: treat it as unsafe, or split the task")
    return uniq


def _cut(seq: list[int], n: int, truncation: str) -> list[int]:
    """``seq`` cut to at most ``n`` tokens (head, or head and tail)."""
    if len(seq) <= n:
        return list(seq)
    if n <= 0:
        return []
    if truncation == "head_tail":
        h = n // 2
        return list(seq[:h]) + list(seq[len(seq) - (n - h):])
    return list(seq[:n])


def pair_windows(prefix: list[int], suffix: list[int], context: list[int], focus: list[int], max_length: int,
                 truncation: str) -> list[list[int]]:
    """The sequences that read a ``(context, focus)`` view in full: one, :func:`pair_ids`, while the
    focus fits (without a context: ``prefix + focus + suffix`` while it fits the whole budget);
    else overlapping windows of the focus (three quarters of the budget each, half of it apart),
    each read after the context and the part of the focus before it (head and tail). No focus
    token is left unread; the caller takes the riskiest window.

    >>> pair_windows([101], [102], [], list(range(1, 13)), 10, "head_tail")  # doctest: +NORMALIZE_WHITESPACE
    [[101, 1, 2, 3, 4, 5, 102], [101, 1, 2, 102, 3, 4, 5, 6, 7, 102], [101, 1, 4, 102, 5, 6, 7, 8, 9, 102],
     [101, 1, 6, 102, 7, 8, 9, 10, 11, 102], [101, 1, 7, 102, 8, 9, 10, 11, 12, 102]]
    """
    budget = max_length - len(prefix) - 2 * len(suffix)
    if budget < 4:
        raise ValueError(f"max_length={max_length} leaves no room for a text pair")
    if not context:
        if len(focus) <= max_length - len(prefix) - len(suffix):
            return [list(prefix) + list(focus) + list(suffix)]
    elif len(focus) <= max(budget * 3 // 4, budget - len(context)):
        return [pair_ids(prefix, suffix, context, focus, max_length, truncation)]
    w = budget * 3 // 4
    stride = max(1, w // 2)
    starts = list(range(0, len(focus) - w, stride)) + [len(focus) - w]
    out = []
    for s in starts:
        out.append(pair_ids(prefix, suffix, list(context) + list(focus[:s]), list(focus[s:s + w]), max_length,
                            truncation))
    return out


def pair_ids(prefix: list[int], suffix: list[int], context: list[int], focus: list[int], max_length: int,
             truncation: str) -> list[int]:
    """``prefix + context + suffix + focus + suffix`` in at most ``max_length`` tokens (both backends).

    The focus is kept whole while it fits in three quarters of the budget; the
    context gets what is left, its head and tail (the start of the scene and what
    comes right before the focus), so a long text never loses its instruction.

    >>> pair_ids([101], [102], list(range(1, 50)), [7, 8, 9], 16, "head_tail")
    [101, 1, 2, 3, 4, 5, 45, 46, 47, 48, 49, 102, 7, 8, 9, 102]
    """
    budget = max_length - len(prefix) - 2 * len(suffix)
    if budget < 4:
        raise ValueError(f"max_length={max_length} leaves no room for a text pair")
    f = _cut(focus, max(budget * 3 // 4, budget - len(context)), truncation)
    c = _cut(context, budget - len(f), truncation)
    return prefix + c + suffix + f + suffix if c else prefix + f + suffix
