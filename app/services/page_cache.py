"""Server-rendered pages (the home page's tables, a case's claims) kept until what they show
changes: the verdict store's `updated` stamp and state (a verdict computed, a check started
or finished) and the template file's modification time. Rendering a page walks the catalogue
and every verdict; a page asked for again is a lookup."""

from __future__ import annotations

import threading
from collections.abc import Callable
from pathlib import Path

from app.services.verdicts import VerdictStore


class PageCache:
    def __init__(self, max_pages: int = 64):
        self.max_pages = max_pages
        self._pages: dict[str, tuple[tuple, str]] = {}
        self._lock = threading.Lock()
        self.renders = 0          # how many times a page was built (tests read it)

    @staticmethod
    def stamp(verdicts: VerdictStore, template: Path) -> tuple:
        return (verdicts.updated, verdicts.state, len(verdicts.records),
                template.stat().st_mtime_ns)

    def get(self, name: str, stamp: tuple, build: Callable[[], str]) -> str:
        with self._lock:
            hit = self._pages.get(name)
        if hit is not None and hit[0] == stamp:
            return hit[1]
        html = build()
        with self._lock:
            self.renders += 1
            if len(self._pages) >= self.max_pages:
                self._pages.clear()
            self._pages[name] = (stamp, html)
        return html
