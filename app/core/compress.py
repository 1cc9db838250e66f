"""Compressed answers: uncompressed, a case page moved megabytes, most of them plotly.js
sent as it is.

- Static files (/static/*, /vendor/plotly.min.js) are compressed once, off the event loop,
  and kept in memory and on disk under Settings.cache_dir/compressed (keyed by path, size
  and modification time, so an upgraded plotly is compressed again). Brotli (quality 11)
  when the client accepts it, else gzip (level 9). A file whose Brotli form is not made
  yet is sent as gzip (made on demand in a thread, quick) while the
  Brotli form is made in the background; `precompress` makes them all at start-up.
- Answers of the routes (HTML pages, JSON) pass through Starlette's GZipMiddleware at
  level 6 (bodies over 128 KiB are compressed in a thread). The Poincaré stream
  (application/x-ndjson) and Arrow answers are not compressed: the stream must reach the
  page trajectory by trajectory, and Arrow's doubles barely shrink.
"""

from __future__ import annotations

import gzip
import hashlib
import logging
import os
import threading
from pathlib import Path

import anyio
from starlette.datastructures import Headers
from starlette.middleware.gzip import DEFAULT_EXCLUDED_CONTENT_TYPES, GZipMiddleware
from starlette.responses import FileResponse, Response
from starlette.staticfiles import StaticFiles

log = logging.getLogger("rolling")

COMPRESSIBLE = {".js", ".mjs", ".css", ".json", ".svg", ".html", ".txt", ".map", ".csv",
                ".md", ".xml", ".ttf", ".otf", ".eot"}
MIN_SIZE = 1024
MAX_SIZE = 32 << 20
# Brotli quality 11 (the densest: plotly.min.js a tenth smaller than at 9); made once per
# file and kept on disk, its much longer compression is paid only the first time
BROTLI_QUALITY = 11
GZIP_LEVEL = 9
NOT_COMPRESSED = (*DEFAULT_EXCLUDED_CONTENT_TYPES, "application/x-ndjson",
                  "application/vnd.apache.arrow.stream")

try:
    import brotli
except ImportError:  # the extra is missing: gzip only
    brotli = None


def accepted(headers: Headers) -> list[str]:
    """The encodings this server can send that the request accepts, best first."""
    offered = {}
    for part in headers.get("accept-encoding", "").lower().split(","):
        name, _, params = part.strip().partition(";")
        q = 1.0
        if params.strip().startswith("q="):
            try:
                q = float(params.strip()[2:])
            except ValueError:
                q = 0.0
        offered[name.strip()] = q
    out = []
    if brotli is not None and offered.get("br", 0) > 0:
        out.append("br")
    if offered.get("gzip", 0) > 0:
        out.append("gzip")
    return out


def _compress(data: bytes, encoding: str) -> bytes:
    if encoding == "br":
        return brotli.compress(data, quality=BROTLI_QUALITY)
    return gzip.compress(data, GZIP_LEVEL, mtime=0)


class AssetCache:
    """path -> its compressed forms, made once (see the module docstring)."""

    def __init__(self, cache_dir: Path | None):
        self.dir = Path(cache_dir) / "compressed" if cache_dir is not None else None
        self._mem: dict[tuple, bytes] = {}
        self._making: set[tuple] = set()
        self._lock = threading.Lock()

    def _key(self, path: Path, encoding: str) -> tuple | None:
        try:
            st = path.stat()
        except OSError:
            return None
        if not MIN_SIZE <= st.st_size <= MAX_SIZE:
            return None
        # the level is part of the key: a form made at another quality is not reused
        level = BROTLI_QUALITY if encoding == "br" else GZIP_LEVEL
        return (str(path), st.st_size, st.st_mtime_ns, encoding, level)

    def _disk(self, key: tuple) -> Path | None:
        if self.dir is None:
            return None
        h = hashlib.sha256(repr(key).encode()).hexdigest()[:32]
        return self.dir / f"{h}.{key[3]}"

    def ready(self, path: Path, encoding: str) -> bytes | None:
        """The compressed form if it is made (memory or disk), else None. Cheap."""
        key = self._key(path, encoding)
        if key is None:
            return None
        if key in self._mem:
            return self._mem[key]
        disk = self._disk(key)
        if disk is not None and disk.is_file():
            try:
                data = disk.read_bytes()
            except OSError:
                return None
            self._mem[key] = data
            return data
        return None

    def make(self, path: Path, encoding: str) -> bytes | None:
        """Compress `path` now (call from a thread); stored in memory and on disk."""
        key = self._key(path, encoding)
        if key is None:
            return None
        got = self.ready(path, encoding)
        if got is not None:
            return got
        data = _compress(path.read_bytes(), encoding)
        self._mem[key] = data
        disk = self._disk(key)
        if disk is not None:
            try:
                disk.parent.mkdir(parents=True, exist_ok=True)
                tmp = disk.with_suffix(disk.suffix + f".{os.getpid()}.tmp")
                tmp.write_bytes(data)
                os.replace(tmp, disk)
            except OSError:   # a read-only cache: memory only
                pass
        return data

    def _background(self, path: Path, encoding: str) -> None:
        key = self._key(path, encoding)
        with self._lock:
            if key is None or key in self._making:
                return
            self._making.add(key)

        def run():
            try:
                _low_priority_thread()
                self.make(path, encoding)
            except Exception as exc:  # serve the other form
                log.warning("compressing %s failed: %r", path, exc)
            finally:
                with self._lock:
                    self._making.discard(key)

        threading.Thread(target=run, daemon=True, name="compress").start()

    async def response(self, path: Path, headers: Headers, plain: Response) -> Response:
        """`plain` (a FileResponse of `path`) or its compressed twin."""
        if (plain.status_code != 200 or path.suffix.lower() not in COMPRESSIBLE
                or "range" in headers):
            return plain
        for enc in accepted(headers):
            data = self.ready(path, enc)
            if data is None and enc == "br":
                self._background(path, enc)      # gzip meanwhile
                continue
            if data is None:
                data = await anyio.to_thread.run_sync(self.make, path, enc)
            if data is None:
                return plain
            out = Response(data, status_code=200)
            for k, v in plain.raw_headers:
                if k not in (b"content-length", b"content-encoding", b"accept-ranges"):
                    out.raw_headers.append((k, v))
            out.headers["content-encoding"] = enc
            out.headers["content-length"] = str(len(data))
            out.headers.add_vary_header("Accept-Encoding")
            return out
        return plain

    def precompress(self, paths: list[Path]) -> int:
        """Make every form of every file (start-up, in a thread); the number made."""
        _low_priority_thread()
        n = 0
        for p in paths:
            for enc in (["br"] if brotli is not None else []) + ["gzip"]:
                if self._key(p, enc) is not None and self.ready(p, enc) is None:
                    self.make(p, enc)
                    n += 1
        return n


def _low_priority_thread() -> None:
    """This thread only (Linux: a thread is a task of its own for the scheduler)."""
    try:
        os.setpriority(os.PRIO_PROCESS, threading.get_native_id(), 10)
    except (OSError, AttributeError):
        pass


def static_paths(static_dir: Path) -> list[Path]:
    return sorted(p for p in Path(static_dir).rglob("*")
                  if p.is_file() and p.suffix.lower() in COMPRESSIBLE)


class CompressedStaticFiles(StaticFiles):
    def __init__(self, *args, assets: AssetCache, **kw):
        super().__init__(*args, **kw)
        self.assets = assets

    async def get_response(self, path: str, scope) -> Response:
        plain = await super().get_response(path, scope)
        if isinstance(plain, FileResponse):
            return await self.assets.response(Path(plain.path), Headers(scope=scope), plain)
        return plain


def install(app, assets: AssetCache) -> None:
    app.add_middleware(GZipMiddleware, minimum_size=MIN_SIZE, compresslevel=6,
                       exclude_content_types=NOT_COMPRESSED)
