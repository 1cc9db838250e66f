"""Which connection to close when the server's connection cap is reached
(app.core.server, GuardedH11Protocol._evict_one): the candidates by kind, each kept in
time order so that a victim is found without a scan of every connection. The ranks and
why they are in that order: Candidates.victim and app.core.server's docstring."""

from __future__ import annotations

from collections import OrderedDict

# the kinds of connection that may be evicted (a connection is in at most one):
#   dead     closed by a read timeout, still lingering
#   head     waiting for a request head; since = the connection, or the first byte of the
#            next request on a keep-alive connection (a trickle does not renew it)
#   body     sending a request body; since = its last byte
#   closing  lingering after an answer (413, 431, 400); since = the close
#   idle     a keep-alive connection between requests; since = the end of the last answer
# Never in any: a request read to its end whose answer is being made or sent, a
# connection closing with no unread input (its answer is being flushed).
KINDS = ("dead", "head", "body", "closing", "idle")

# a body arriving at least this fast (its bytes over the request's age, an age of at least
# RATE_FLOOR_S) is a real upload, not a trickle: the slowest-request rank passes over it.
# A trickle of a byte every half second is some bytes a second; a JSON body comes in one
# piece. Heads are not rated: a head's bytes come in one piece or they are a stall.
FAST_BYTES_S = 16 * 1024
RATE_FLOOR_S = 0.1
# the slowest request is looked for among this many of the oldest requests in progress,
# so that choosing a victim stays cheap when many of them are fast uploads
SLOW_SCAN = 32


class Candidates:
    """The evictable connections of one server, by kind. Each kind is an insertion-ordered
    dict protocol -> since, and every (re)insertion is made with since = now, so that each
    dict is ordered by `since` (time is monotonic) and its oldest entry is its first: a
    victim is found in O(1), whatever the number of connections. `inflight` holds the
    requests still arriving (the heads and the bodies) by the time they began."""

    def __init__(self) -> None:
        self.kinds: dict[str, OrderedDict] = {k: OrderedDict() for k in KINDS}
        self.inflight: OrderedDict = OrderedDict()

    @staticmethod
    def _first(d: OrderedDict, skip=None):
        for p, since in d.items():
            if skip is None or not skip(p):
                return since, p
        return None

    def _slowest(self, now: float):
        """Among the SLOW_SCAN oldest requests in progress: the oldest body that trickles
        (not paused by the app, arriving below FAST_BYTES_S), else the oldest head. A
        body goes first: its sender has shown how slowly it sends, while a head not read
        yet may be a client's that is about to arrive (on a busy client, a connection's
        first bytes can follow it by a good part of a second)."""
        head = None
        for n, (p, since) in enumerate(self.inflight.items()):
            if n >= SLOW_SCAN:
                break
            if p._kind != "body":
                head = head or p
            elif not (p.flow.read_paused or p._in_bytes
                      >= FAST_BYTES_S * max(now - since, RATE_FLOOR_S)):
                return p
        return head

    def victim(self, now: float, grace: float):
        """(connection, rank) to evict, or None. The ranks, in order:
        stalled     a timed-out connection still lingering; else the longest silent of a
                    head, a body (not paused by the app) or a lingering answer, once
                    silent for `grace` seconds;
        slowest     of the requests still arriving, the trickling body that began the
                    longest ago (not a fast upload), else the oldest head (a flood of
                    fresh sockets or of trickling bodies evicts its own oldest; a client's
                    request arrives in one piece and is the youngest);
        idle        a keep-alive connection between requests, idle the longest first;
        young_body  a fast body or a lingering answer silent for less than `grace`, the
                    longest silent first (a streaming body's last byte is milliseconds old)."""
        k = self.kinds
        if k["dead"]:
            return next(iter(k["dead"])), "stalled"
        # a body whose reading the app paused (it has not read what came) is not stalled
        fronts = [f for f in (self._first(k["head"]),
                              self._first(k["body"], lambda p: p.flow.read_paused),
                              self._first(k["closing"])) if f is not None]
        oldest = min(fronts, key=lambda f: f[0]) if fronts else None
        if oldest is not None and now - oldest[0] >= grace:
            return oldest[1], "stalled"
        slow = self._slowest(now)
        if slow is not None:
            return slow, "slowest"
        if k["idle"]:
            return next(iter(k["idle"])), "idle"
        if oldest is not None:
            return oldest[1], "young_body"
        return None
