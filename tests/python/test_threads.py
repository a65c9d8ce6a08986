"""Builds and queries release the GIL: two Python threads build at once, and give the maps one thread gives."""
import threading
import time

import numpy as np

import hairshadow as hs
from conftest import sample_points


def test_two_threads_build_at_once_and_agree(sintel):
    specs = ["dom:3", "occ:64:2"]
    alone = {}
    for spec in specs:
        m = hs.ShadowMap(spec)
        m.build(sintel, resolution=256, threads=1)
        alone[spec] = m.maps_hash
    together, errors = {}, []

    def build(spec):
        try:
            m = hs.ShadowMap(spec)
            for _ in range(3):
                m.build(sintel, resolution=256)
            together[spec] = m.maps_hash
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    threads = [threading.Thread(target=build, args=(s,)) for s in specs]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert together == alone


def test_the_gil_is_released_while_building_and_querying(sintel):
    """While another thread builds and queries, this one keeps running: the longest pause it sees is
    under half of one build or query (one that held the GIL would stop it for all of it). The work
    runs on one library thread, so that this thread keeps a core of its own."""
    m = hs.ShadowMap("dom:3")
    points = sample_points(sintel, 1_000_000)

    def timed(call):
        start = time.perf_counter()
        call()
        return time.perf_counter() - start

    def build():
        m.build(sintel, resolution=2048, threads=1)

    def query():
        m.transmittance(points, threads=1)

    build()
    one_build, one_query = timed(build), timed(query)
    done = threading.Event()

    def work():
        for _ in range(3):
            build()
            query()
        done.set()

    worker = threading.Thread(target=work)
    worker.start()
    longest, last = 0.0, time.perf_counter()
    while not done.is_set():
        now = time.perf_counter()
        longest, last = max(longest, now - last), now
    worker.join()
    assert longest < 0.5 * min(one_build, one_query), (longest, one_build, one_query)


def test_one_map_queried_by_many_threads(small):
    m = hs.ShadowMap("fom:7")
    m.build(small, resolution=64)
    points = sample_points(small, 20000)
    expected = m.transmittance(points)
    results = [None] * 4

    def query(i):
        results[i] = m.transmittance(points)

    threads = [threading.Thread(target=query, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        np.testing.assert_array_equal(r, expected)


def test_queries_during_rebuilds_of_the_same_map(small):
    """A build takes the map's lock: a query never sees half-built maps (a rebuild gives the same maps)."""
    m = hs.ShadowMap("occ:128:4")
    m.build(small, resolution=256)
    points = sample_points(small, 50000)
    expected = m.transmittance(points)
    done, seen = threading.Event(), []

    def rebuild():
        for _ in range(20):
            m.build(small, resolution=256)
        done.set()

    worker = threading.Thread(target=rebuild)
    worker.start()
    while not done.is_set():
        seen.append(np.array_equal(m.transmittance(points), expected))
    worker.join()
    assert seen and all(seen)
