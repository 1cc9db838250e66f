"""The worker pool behind the CPU routes (app/core/pool.py), against a real uvicorn:
deadline, bounded queue (503 + Retry-After), cancellation when the client goes away."""

import json
import statistics
import threading
import time

import httpx
import pytest

from app.testing import live_server, wait_idle

# a run no deadline here lets finish: 1e7 time units at rtol 1e-16 are some 7e7 steps of the
# warm dop853 kernel, several times the patient deadline (at the default rtol 1e-10 they
# take a few seconds, near it)
LONG = {"case": "plane/chaplygin-ball", "example": True, "t_end": 1e7, "samples": 11,
        "rtol": 1e-16, "atol": 1e-16}
SHORT = {"case": "plane/chaplygin-ball", "example": True, "t_end": 10, "samples": 11}


def _one_worker_server(deadline_s):
    """One worker, one waiting place, this deadline and no step budget to speak of."""
    with live_server(workers=1, queue_size=1, deadline_s=deadline_s, max_steps=10**9,
                     retry_after_s=3) as url:
        wait_idle(url)
        yield url


@pytest.fixture(scope="module")
def server():
    yield from _one_worker_server(1.5)


def health(url):
    return httpx.get(f"{url}/api/health", timeout=5).json()


def test_deadline_kills_the_run_and_says_so(server):
    before = health(server)["pool"]["timed_out"]
    t0 = time.monotonic()
    r = httpx.post(f"{server}/api/simulate", json=LONG, timeout=30)
    assert 1.4 < time.monotonic() - t0 < 10
    # a limit of the server, not bad input (issue 9): 504 with a message
    assert r.status_code == 504
    assert "1.5 s" in r.json()["detail"] and "t_end" in r.json()["detail"]
    assert health(server)["pool"]["timed_out"] == before + 1
    # the killed worker is replaced: the next run works
    assert httpx.post(f"{server}/api/simulate", json=SHORT, timeout=30).status_code == 200


@pytest.fixture(scope="module")
def patient_server():
    # the queue and cancellation tests must see their state before any deadline fires:
    # a deadline long enough that a loaded machine (CI runs two test workers on two
    # cores) cannot let it fire first
    yield from _one_worker_server(5.0)


def wait_pool(url, running, waiting, timeout=4.0):
    """Poll /api/health until the pool holds `running` and `waiting` requests."""
    deadline = time.monotonic() + timeout
    while True:
        h = health(url)["pool"]
        if (h["running"], h["waiting"]) == (running, waiting) or time.monotonic() > deadline:
            return h
        time.sleep(0.05)


def test_full_queue_is_503_with_retry_after(patient_server):
    server = patient_server
    results = []

    def long_run():
        results.append(httpx.post(f"{server}/api/simulate", json=LONG, timeout=30).status_code)

    threads = [threading.Thread(target=long_run) for _ in range(2)]
    threads[0].start()
    h = wait_pool(server, running=1, waiting=0)
    assert (h["running"], h["waiting"]) == (1, 0)
    threads[1].start()
    h = wait_pool(server, running=1, waiting=1)
    assert (h["running"], h["waiting"]) == (1, 1)
    r = httpx.post(f"{server}/api/simulate", json=SHORT, timeout=10)
    assert r.status_code == 503
    assert r.headers["retry-after"] == "3"
    assert "busy" in r.json()["detail"]
    # bad input is still judged at once, even with the queue full
    bad = httpx.post(f"{server}/api/simulate", json={**SHORT, "t_end": -1}, timeout=10)
    assert bad.status_code == 422
    for t in threads:
        t.join()
    assert results == [504, 504]   # both reached their deadline


def test_client_going_away_cancels_the_worker(patient_server):
    server = patient_server
    wait_idle(server)
    before = health(server)["pool"]
    with pytest.raises(httpx.ReadTimeout):
        httpx.post(f"{server}/api/simulate", json=LONG, timeout=0.8)
    deadline = time.monotonic() + 3.0      # well before the 5 s deadline would fire
    while time.monotonic() < deadline:
        h = health(server)["pool"]
        if h["cancelled"] > before["cancelled"] and h["running"] == 0:
            break
        time.sleep(0.05)
    assert h["cancelled"] == before["cancelled"] + 1
    assert h["running"] == 0
    assert h["timed_out"] == before["timed_out"]
    assert httpx.post(f"{server}/api/simulate", json=SHORT, timeout=30).status_code == 200


def test_health_is_not_blocked_by_a_running_simulation(patient_server):
    """Relative, not absolute (shared machines are noisy): health is answered again and
    again WHILE a simulation runs (if the event loop ran the simulation, no answer could
    come before it ends), each answer a fraction of that run's duration. (The 5 s server:
    the run of about a second took over 1.5 s on a loaded machine, the other's deadline.)"""
    server = patient_server
    wait_idle(server)
    # the worker loads the case's small kernel on its first run of it (from the on-disk
    # cache); a fresh-clone CI dry run saw this test's run reach the 5 s deadline (504)
    # at load ~4, the cause not isolated: a short run first, so that the timed run is a
    # run of a warm worker and the test measures the event loop, not a first load
    assert httpx.post(f"{server}/api/simulate", json=SHORT, timeout=60).status_code == 200
    # about a second of integration, then it returns (the generated field runs the ball's
    # 1e6 time units in ~1.2 s; 5e4 took that long on the general field)
    busy = {**SHORT, "t_end": 1e6}
    done = {}

    def run():
        t0 = time.perf_counter()
        done["status"] = httpx.post(f"{server}/api/simulate", json=busy,
                                    timeout=60).status_code
        done["seconds"] = time.perf_counter() - t0

    t = threading.Thread(target=run)
    t.start()
    for _ in range(200):                      # until the worker has the job
        if httpx.get(f"{server}/api/health", timeout=30).json()["pool"]["running"] >= 1:
            break
        time.sleep(0.02)
    times, during = [], 0
    while t.is_alive() and len(times) < 20:
        t0 = time.perf_counter()
        r = httpx.get(f"{server}/api/health", timeout=30)
        times.append(time.perf_counter() - t0)
        assert r.status_code == 200
        during += r.json()["pool"]["running"] >= 1
    t.join()
    assert done["status"] == 200
    assert during >= 3, (during, times)
    assert statistics.median(times) < done["seconds"] / 3, (times, done)


MAP = {"case": "plane/chaplygin-ball", "example": True, "energy": 1.0, "section": "g=0",
       "trajectories": 32, "points": 5000}


@pytest.mark.parametrize("stream", [False, True])
def test_one_deadline_for_a_whole_poincare_request(server, stream):
    """32 trajectories of 5000 crossings take far longer than the 1.5 s deadline in total
    (one at a time on one worker): the request stops at 1.5 s, not 1.5 s per trajectory,
    and says so in words that fit a map."""
    wait_idle(server)
    t0 = time.monotonic()
    r = httpx.post(f"{server}/api/poincare", json=MAP, params={"stream": stream}, timeout=60)
    elapsed = time.monotonic() - t0
    assert elapsed < 6, elapsed
    if stream:
        events = [json.loads(line) for line in r.text.splitlines()]
        last = events[-1]
        assert last["event"] == "error" and last["status"] == 504, events[-2:]
        detail = last["detail"]
    else:
        assert r.status_code == 504, r.text[:300]
        detail = r.json()["detail"]
    assert "1.5 s" in detail and "points" in detail and "t_end" not in detail
