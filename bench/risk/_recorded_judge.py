"""A loopback OpenAI-compatible judge server that answers from recorded verdicts (stdlib only).

The whole-tier bench (``risk_tiers.py``) asks ethimon's real :class:`~ethimon.risk.Judge` client, with
its canary gate, consensus and parsing, against this server; the server looks each task text up in a
table of recorded answers (a capable LLM's verdicts kept in ``data/judge_recorded/``) or answers by a
fixed behaviour, so a failing judge is measured through the same code path as a good one.

Models (the ``model`` field of a request):

* ``recorded:<NAME>``: the recorded verdict of judge NAME for this text (token ``0``/``1``, logprobs
  p 0.01 / 0.99); a text NAME never answered gets an answer of ``?`` (no verdict: the client refuses it);
* ``const:0`` / ``const:1``: the same verdict for every text (a stub left running);
* ``coin``: a fair coin per request (seeded);
* any other name: HTTP 404 ``model not found`` (a wrong model name).
"""

from __future__ import annotations

import json
import math
import random
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer


def _reply(token: str, p_one: float | None) -> bytes:
    ch = {"index": 0, "message": {"role": "assistant", "content": token}, "finish_reason": "length"}
    if p_one is not None:
        lp1, lp0 = math.log(p_one), math.log(1.0 - p_one)
        ch["logprobs"] = {"content": [{"token": token, "logprob": lp1 if token == "1" else lp0,
                                       "top_logprobs": [{"token": "1", "logprob": lp1}, {"token": "0", "logprob": lp0}]}]}
    return json.dumps({"id": "r", "object": "chat.completion", "model": "recorded", "choices": [ch]}).encode()


class RecordedJudgeServer:
    """``with RecordedJudgeServer(tables) as url:`` serves ``url`` (``http://127.0.0.1:PORT/v1``) until exit.

    ``tables``: judge name -> {user message (``judge_user_message(text)``) -> verdict 0/1}.
    """

    def __init__(self, tables: dict[str, dict[str, int]], seed: int = 0) -> None:
        self.tables = tables
        self.rng = random.Random(seed)
        self.lock = threading.Lock()
        self.requests = 0
        outer = self

        class H(BaseHTTPRequestHandler):
            protocol_version = "HTTP/1.1"

            def log_message(self, *a):  # quiet
                pass

            def _send(self, code: int, data: bytes) -> None:
                self.send_response(code)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(data)))
                self.end_headers()
                self.wfile.write(data)

            def do_POST(self):  # noqa: N802 - http.server's name
                n = int(self.headers.get("Content-Length") or 0)
                body = json.loads(self.rfile.read(n) or b"{}")
                model = str(body.get("model", ""))
                user = next((m.get("content", "") for m in body.get("messages", []) if m.get("role") == "user"), "")
                with outer.lock:
                    outer.requests += 1
                    coin = outer.rng.random() < 0.5
                if model.startswith("recorded:"):
                    v = outer.tables.get(model.split(":", 1)[1], {}).get(user)
                    data = _reply("?", None) if v is None else _reply(str(v), 0.99 if v else 0.01)
                elif model in ("const:0", "const:1"):
                    v = int(model[-1])
                    data = _reply(str(v), 0.99 if v else 0.01)
                elif model == "coin":
                    data = _reply("1" if coin else "0", 0.99 if coin else 0.01)
                else:
                    return self._send(404, json.dumps({"error": {"message": f"model {model!r} not found"}}).encode())
                self._send(200, data)

        self.httpd = ThreadingHTTPServer(("127.0.0.1", 0), H)
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)

    def __enter__(self) -> str:
        self.thread.start()
        return f"http://127.0.0.1:{self.httpd.server_address[1]}/v1"

    def __exit__(self, *exc: object) -> None:
        self.httpd.shutdown()
        self.httpd.server_close()
