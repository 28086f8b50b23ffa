"""Widget callbacks run on the main thread, in order (see halfedge_edu.viz.main_thread)."""

from __future__ import annotations

import threading

from tornado.ioloop import IOLoop

from halfedge_edu.viz.main_thread import call_on_main_thread, kernel_loop, on_main_thread


def test_a_call_on_the_main_thread_runs_at_once():
    ran = []
    on_main_thread(lambda value: ran.append((value, threading.current_thread())))(7)
    assert ran == [(7, threading.main_thread())]


def test_calls_from_other_threads_run_on_the_main_thread_in_order():
    loop = IOLoop(make_current=False)
    ran: list[tuple[int, threading.Thread]] = []
    n_calls = 40

    def record(k: int) -> None:
        ran.append((k, threading.current_thread()))
        if len(ran) == n_calls:
            loop.stop()

    wrapped = on_main_thread(record, loop=loop)

    def sender() -> None:
        # One thread, like the kernel's subshell, sends the calls one after another.
        for k in range(n_calls):
            wrapped(k)

    thread = threading.Thread(target=sender, name="subshell-test")
    loop.add_callback(thread.start)
    loop.call_later(10.0, loop.stop)            # a safety net: the test fails, it does not hang
    loop.start()
    thread.join()
    loop.close()
    assert [k for k, _ in ran] == list(range(n_calls))
    assert {t for _, t in ran} == {threading.main_thread()}


def test_a_call_from_another_thread_waits_for_the_loop():
    loop = IOLoop(make_current=False)
    ran = []
    thread = threading.Thread(target=call_on_main_thread, args=(ran.append, "clicked"), kwargs={"loop": loop})
    thread.start()
    thread.join()
    assert ran == []                            # queued, not run on the calling thread
    loop.add_callback(loop.stop)
    loop.start()
    loop.close()
    assert ran == ["clicked"]


def test_outside_a_kernel_there_is_no_loop_and_the_call_runs_where_it_is():
    assert kernel_loop() is None
    ran = []
    thread = threading.Thread(target=call_on_main_thread, args=(lambda: ran.append(threading.current_thread()),))
    thread.start()
    thread.join()
    assert ran == [thread]
