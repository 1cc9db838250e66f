"""Safe defaults of a local server, as pure ASGI middleware (app.core.disconnect needs the raw
`receive`, so no BaseHTTPMiddleware):

- `SecurityHeaders`: nosniff, a Content-Security-Policy that allows only this server (the
  explorer loads nothing from elsewhere), no framing, no referrer, on every response;
- `HeadAsGet`: HEAD is answered like GET without the body (pages, API, static files);
- `RequestGuard`: for requests that carry a body or change state (POST, PUT, PATCH,
  DELETE): a foreign `Origin` is 403 (a page of another site cannot make a browser run a
  verification here), a content type other than JSON is 415 (a cross-site HTML form can
  only send form or text types; a request with neither a body nor a content type is left
  to the route, which knows whether it exists: app.api.deps.JSON_ONLY), and a body over
  `max_body` bytes is 413, counted from Content-Length and from the streamed chunks,
  before anything parses it. Bodies are read in full only up to that limit, so a 50 MB
  upload neither stalls the event loop nor fills the memory. Every answer of the guard
  says `Connection: close`: the rest of the body is never read. The server's protocol
  (app.core.server) stops reading, sends the answer and closes the socket a moment
  later, so the discarded bytes never pass through the event loop and a client still
  sending has the time to read the answer.
- `HeaderLimit`: a request with more than `max_headers` header fields is 431 (their total
  size is bounded by the server's parser, app.core.server).

The Host allow-list (DNS rebinding) is Starlette's TrustedHostMiddleware, set up in
app.main from Settings.trusted_hosts().
"""

from __future__ import annotations

import json
from collections.abc import Awaitable, Callable, MutableMapping
from typing import Any

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]

# everything is served by this app: scripts, styles, fonts, data. 'unsafe-inline' for
# styles only: plotly.js writes style attributes and <style> rules at run time.
CSP = ("default-src 'self'; script-src 'self'; style-src 'self' 'unsafe-inline'; "
       "img-src 'self' data: blob:; font-src 'self'; connect-src 'self'; "
       "worker-src 'self' blob:; object-src 'none'; base-uri 'self'; form-action 'self'; "
       "frame-ancestors 'none'")
HEADERS = [(b"x-content-type-options", b"nosniff"),
           (b"x-frame-options", b"DENY"),
           (b"referrer-policy", b"no-referrer"),
           (b"content-security-policy", CSP.encode())]
UNSAFE_METHODS = {"POST", "PUT", "PATCH", "DELETE"}


class SecurityHeaders:
    """Adds HEADERS to every response that does not set its own value (/docs sets a CSP
    that lets Swagger UI run its inline start-up script)."""

    def __init__(self, app: ASGIApp):
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            return await self.app(scope, receive, send)

        async def send_with_headers(message: Message) -> None:
            if message["type"] == "http.response.start":
                headers = list(message.get("headers", []))
                have = {k.lower() for k, _ in headers}
                headers += [(k, v) for k, v in HEADERS if k not in have]
                message = {**message, "headers": headers}
            await send(message)

        await self.app(scope, receive, send_with_headers)


class HeadAsGet:
    """HEAD runs the GET route and sends its status and headers (Content-Length included)
    without the body."""

    def __init__(self, app: ASGIApp):
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http" or scope["method"] != "HEAD":
            return await self.app(scope, receive, send)

        async def send_no_body(message: Message) -> None:
            if message["type"] == "http.response.body":
                message = {**message, "body": b""}
            await send(message)

        await self.app({**scope, "method": "GET"}, receive, send_no_body)


def _problem(status: int, detail: str, kind: str) -> tuple[dict, bytes]:
    loc = {"origin": ["header", "origin"], "headers": ["header"]}.get(kind, ["body"])
    body = json.dumps({"detail": detail, "errors": [
        {"loc": loc, "msg": detail, "type": kind}]}).encode()
    # the body of the request (if any) is not read: the connection ends with this answer
    start = {"type": "http.response.start", "status": status,
             "headers": [(b"content-type", b"application/json"),
                         (b"content-length", str(len(body)).encode()),
                         (b"connection", b"close")]}
    return start, body


async def _answer(send: Send, status: int, detail: str, kind: str) -> None:
    start, body = _problem(status, detail, kind)
    await send(start)
    await send({"type": "http.response.body", "body": body})


def _header(scope: Scope, name: bytes) -> str | None:
    for k, v in scope.get("headers", []):
        if k.lower() == name:
            return v.decode("latin-1")
    return None


def not_json(content_type: str | None) -> str:
    """The 415 answer's message for a content type that is not JSON (or none)."""
    shown = (content_type or "none")[:80]
    return (f"content type {shown!r} is not accepted: send the body as JSON with "
            "Content-Type: application/json")


def is_json(content_type: str) -> bool:
    media = content_type.split(";", 1)[0].strip().lower()
    return media == "application/json" or (media.startswith("application/")
                                           and media.endswith("+json"))


class HeaderLimit:
    def __init__(self, app: ASGIApp, max_headers: int = 100):
        self.app = app
        self.max_headers = max_headers

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http" and len(scope.get("headers", ())) > self.max_headers:
            return await _answer(send, 431, f"the request has {len(scope['headers'])} header "
                                 f"fields; this server accepts at most {self.max_headers}",
                                 "headers")
        await self.app(scope, receive, send)


class RequestGuard:
    def __init__(self, app: ASGIApp, max_body: int = 1 << 20,
                 allowed_origins: tuple[str, ...] = ()):
        self.app = app
        self.max_body = max_body
        self.allowed_origins = {o.rstrip("/").lower() for o in allowed_origins}

    def _origin_ok(self, scope: Scope, origin: str) -> bool:
        origin = origin.rstrip("/").lower()
        if origin in self.allowed_origins:
            return True
        host = (_header(scope, b"host") or "").lower()
        return bool(host) and origin == f"{scope.get('scheme', 'http')}://{host}"

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http" or scope["method"] not in UNSAFE_METHODS:
            return await self.app(scope, receive, send)
        origin = _header(scope, b"origin")
        if origin is not None and not self._origin_ok(scope, origin):
            return await _answer(send, 403, f"origin {origin[:100]!r} may not call this "
                                 "server: requests that change state are accepted from its "
                                 "own pages only (Settings.allowed_origins adds others)",
                                 "origin")
        length = _header(scope, b"content-length")
        chunked = "chunked" in (_header(scope, b"transfer-encoding") or "").lower()
        ctype = _header(scope, b"content-type")
        has_body = chunked or (length is not None and length.strip() not in ("", "0"))
        if (ctype is not None or has_body) and not is_json(ctype or ""):
            return await _answer(send, 415, not_json(ctype), "content_type")
        too_big = (f"the body is larger than {self.max_body} bytes "
                   f"({self.max_body / (1 << 20):g} MB), the limit of this server")
        if length is not None:
            try:
                declared = int(length)
            except ValueError:
                return await _answer(send, 400, "Content-Length is not a number", "header")
            if declared > self.max_body:
                return await _answer(send, 413, too_big, "body_too_large")
        # read the body here, up to the limit, then hand it to the app as it came
        messages: list[Message] = []
        size = 0
        while True:
            message = await receive()
            if message["type"] != "http.request":    # the client went away
                messages.append(message)
                break
            size += len(message.get("body", b""))
            if size > self.max_body:
                return await _answer(send, 413, too_big, "body_too_large")
            messages.append(message)
            if not message.get("more_body", False):
                break

        async def replay() -> Message:
            if messages:
                return messages.pop(0)
            return await receive()     # after the body: the disconnect watch

        await self.app(scope, replay, send)
