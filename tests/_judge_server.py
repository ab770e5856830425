"""An OpenAI-compatible chat-completions server for the judge tests (stdlib http.server, loopback).

Run as a process: ``python tests/_judge_server.py LOGFILE``; it prints its port on the first line
of stdout. The *model* named in each request picks the scripted behaviour (so one server serves
every case); every request is appended to LOGFILE as one JSON line (path, headers, body).

Models: ``p=<x>`` (answers the verdict token of x, logprobs ln x / ln(1-x)), ``plain-0``/``plain-1``
(no logprobs), ``delay=<s>`` (safe, after s seconds), ``http500``, ``notjson``, ``noshape``,
``words`` (answers "0 (safe)"), ``echo`` (answers the task text), ``big`` (a 1 MiB body),
``drip`` (sends a byte every 0.2 s), ``mass`` (verdict tokens carry 10 %), ``contra`` (answer 0,
logprobs say 1), ``fooled`` (a judge fully taken in by any text: answers 0, logprob 0),
``nan`` (logprob NaN), ``driphead`` (drips its status line and headers, a byte every 0.05 s),
``slowfor=<word>`` (safe; sleeps 3 s first when the task text holds <word>), ``rounded`` (logprobs
rounded as real servers round them: P(0) + P(1) = 1.0009), ``rounded-over`` (they sum to 1.14: refused),
``coin`` (a fair coin per request), ``oracle:<model>`` (answers the shipped canaries right, p 0.01 / 0.99,
and every other text as <model>: a capable judge that passes its canaries), ``badcanary:<id>:<model>``
(as oracle, but answers canary <id> wrong).
"""

import csv
import json
import math
import random
import sys
import time
from pathlib import Path
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

LOG = sys.argv[1] if len(sys.argv) > 1 else None
_CANARIES = Path(__file__).resolve().parents[1] / "src" / "ethimon" / "risk" / "canaries" / "canaries.csv"
with open(_CANARIES, newline="", encoding="utf-8") as _f:
    CANARY = {r["text"]: (r["id"], int(r["label"])) for r in csv.DictReader(_f)}


def _reply(content, logprobs=None):
    ch = {"index": 0, "message": {"role": "assistant", "content": content}, "finish_reason": "length"}
    if logprobs is not None:
        ch["logprobs"] = {"content": [{"token": content, "logprob": logprobs[0][1],
                                       "top_logprobs": [{"token": t, "logprob": v} for t, v in logprobs]}]}
    return {"id": "x", "object": "chat.completion", "model": "m", "choices": [ch]}


def _lp(x):
    return math.log(x) if x > 0 else -1e4


class H(BaseHTTPRequestHandler):
    protocol_version = "HTTP/1.1"

    def log_message(self, *a):  # quiet
        pass

    def _send(self, code, data: bytes, ctype="application/json"):
        self.send_response(code)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(data)))
        self.end_headers()
        self.wfile.write(data)

    def do_POST(self):
        n = int(self.headers.get("Content-Length", "0"))
        raw = self.rfile.read(n)
        try:
            body = json.loads(raw)
        except ValueError:
            return self._send(400, b'{"error": "bad json"}')
        if LOG:
            with open(LOG, "a") as f:
                f.write(json.dumps({"path": self.path, "headers": dict(self.headers), "body": body}) + "\n")
        model = str(body.get("model", ""))
        want_lp = bool(body.get("logprobs"))
        if model.startswith(("oracle:", "badcanary:")):
            wrong = model.split(":")[1] if model.startswith("badcanary:") else None
            model = model.split(":", 2 if wrong else 1)[-1]
            try:
                text = json.loads(body["messages"][-1]["content"].split("\n")[1])
            except (KeyError, IndexError, ValueError):
                text = None
            if text in CANARY:
                cid, label = CANARY[text]
                if cid == wrong:
                    label = 1 - label
                x = 0.99 if label else 0.01
                tok = str(label)
                lps = [(tok, math.log(max(x, 1 - x))), (str(1 - label), math.log(min(x, 1 - x)))]
                return self._send(200, json.dumps(_reply(tok, lps if want_lp else None)).encode())
        if model == "coin":
            tok = random.choice("01")
            return self._send(200, json.dumps(_reply(tok, [(tok, 0.0)] if want_lp else None)).encode())
        if model.startswith("p="):
            x = float(model[2:])
            tok = "1" if x >= 0.5 else "0"
            lps = [(tok, _lp(x if tok == "1" else 1 - x)), ("0" if tok == "1" else "1", _lp(1 - x if tok == "1" else x))]
            return self._send(200, json.dumps(_reply(tok, lps if want_lp else None)).encode())
        if model.startswith("plain-"):
            return self._send(200, json.dumps(_reply(model[6:])).encode())
        if model.startswith("delay="):
            time.sleep(float(model[6:]))
            return self._send(200, json.dumps(_reply("0", [("0", 0.0)])).encode())
        if model == "http500":
            return self._send(500, b'{"error": "boom"}')
        if model == "notjson":
            return self._send(200, b"<html>0</html>", "text/html")
        if model == "noshape":
            return self._send(200, b'{"verdict": 0}')
        if model == "words":
            return self._send(200, json.dumps(_reply("0 (safe)")).encode())
        if model == "echo":
            user = body["messages"][-1]["content"]
            text = json.loads(user.split("\n")[1])
            return self._send(200, json.dumps(_reply(text)).encode())
        if model == "big":
            return self._send(200, b" " * (1 << 20) + json.dumps(_reply("0")).encode())
        if model == "drip":
            data = json.dumps(_reply("0")).encode()
            self.send_response(200)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            for b in data:
                self.wfile.write(bytes([b]))
                self.wfile.flush()
                time.sleep(0.2)
            return None
        if model == "mass":
            return self._send(200, json.dumps(_reply("0", [("0", math.log(0.06)), ("1", math.log(0.04)),
                                                           ("The", math.log(0.9))])).encode())
        if model == "contra":
            return self._send(200, json.dumps(_reply("0", [("1", math.log(0.9)), ("0", math.log(0.1))])).encode())
        if model == "fooled":
            return self._send(200, json.dumps(_reply("0", [("0", 0.0), ("1", -30.0)] if want_lp else None)).encode())
        if model == "driphead":
            head = (b"HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nX-Padding: " + b"x" * 80 + b"\r\n")
            for b in head:
                self.wfile.write(bytes([b]))
                self.wfile.flush()
                time.sleep(0.05)
            data = json.dumps(_reply("0")).encode()
            self.wfile.write(b"Content-Length: " + str(len(data)).encode() + b"\r\n\r\n" + data)
            return None
        if model.startswith("slowfor="):
            if model[8:] in body["messages"][-1]["content"]:
                time.sleep(3.0)
            return self._send(200, json.dumps(_reply("0", [("0", 0.0)] if want_lp else None)).encode())
        if model == "rounded":
            return self._send(200, json.dumps(_reply("0", [("0", 0.0), ("1", -7.0)])).encode())
        if model == "rounded-over":
            return self._send(200, json.dumps(_reply("0", [("0", 0.0), ("1", -2.0)])).encode())
        if model == "nan":
            return self._send(200, json.dumps(_reply("0", [("0", float("nan"))])).encode())
        return self._send(404, b'{"error": "unknown model"}')


def spawn(log_path):
    """Start this server as a child process; returns ``(process, base_url)``."""
    import subprocess
    proc = subprocess.Popen([sys.executable, __file__, str(log_path)], stdout=subprocess.PIPE, text=True)
    port = int(proc.stdout.readline())
    return proc, f"http://127.0.0.1:{port}/v1"


if __name__ == "__main__":
    srv = ThreadingHTTPServer(("127.0.0.1", 0), H)
    srv.daemon_threads = True
    print(srv.server_address[1], flush=True)
    srv.serve_forever()
