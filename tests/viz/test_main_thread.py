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


# The same in a real kernel, driven the way JupyterLab 4 drives it (issue 11): a widget
# click is a comm_msg whose header names the comm target's subshell. The kernel runs the
# first click of a comm on its main thread; once the callback has published an update
# under that message, it routes the comm's later messages to the subshell's own thread,
# and on_main_thread must hand those to the main thread's loop, which runs them at once:
# no other message has to arrive to wake it.
KERNEL_SETUP = '''
import threading
import ipywidgets as widgets
from halfedge_edu.viz import on_main_thread

ran = []                     # the thread each click ran on
arrived = []                 # the thread each click arrived on
button = widgets.Button(description="0")
button.on_click(lambda _: arrived.append(threading.current_thread().name))


def clicked(_):
    ran.append(threading.current_thread().name)
    button.description = str(len(ran))


button.on_click(on_main_thread(clicked))
'''
KERNEL_TIMEOUT = 60.0       # seconds: start a kernel and import the widgets on a loaded machine
CLICK_TIMEOUT = 10.0        # seconds for a click's update to come back; it takes milliseconds


def _user_expression(client, expression: str) -> str:
    reply = client.execute_interactive("", user_expressions={"value": expression}, timeout=KERNEL_TIMEOUT)
    return reply["content"]["user_expressions"]["value"]["data"]["text/plain"]


def _wait_for_description(client, comm_id: str, description: str) -> None:
    """Read IOPub (which sends nothing to the kernel) until the button's update arrives."""
    import queue
    import time

    deadline = time.monotonic() + CLICK_TIMEOUT
    while time.monotonic() < deadline:
        try:
            message = client.get_iopub_msg(timeout=max(0.0, deadline - time.monotonic()))
        except queue.Empty:
            break
        content = message["content"]
        if (message["header"]["msg_type"] == "comm_msg" and content.get("comm_id") == comm_id
                and content["data"].get("state", {}).get("description") == description):
            return
    raise AssertionError(f"click {description} was not run within {CLICK_TIMEOUT:.0f} s")


def test_in_a_real_kernel_every_click_runs_on_the_main_thread_at_once():
    from jupyter_client.manager import start_new_kernel

    manager, client = start_new_kernel(kernel_name="python3", startup_timeout=KERNEL_TIMEOUT)
    try:
        reply = client.execute_interactive(KERNEL_SETUP, timeout=KERNEL_TIMEOUT)
        assert reply["content"]["status"] == "ok"
        comm_id = _user_expression(client, "button.comm.comm_id").strip("'")
        client.control_channel.send(client.session.msg("create_subshell_request", {}))
        subshell = client.control_channel.get_msg(timeout=KERNEL_TIMEOUT)["content"]["subshell_id"]
        n_clicks = 3
        for k in range(1, n_clicks + 1):
            click = client.session.msg("comm_msg", {"comm_id": comm_id,
                                                    "data": {"method": "custom", "content": {"event": "click"}}})
            click["header"]["subshell_id"] = subshell
            client.shell_channel.send(click)
            _wait_for_description(client, comm_id, str(k))
        assert _user_expression(client, "ran") == repr(["MainThread"] * n_clicks)
        # The later clicks did arrive on the subshell's thread (else this test shows nothing).
        arrived = _user_expression(client, "arrived")
        assert arrived != repr(["MainThread"] * n_clicks), arrived
    finally:
        client.stop_channels()
        manager.shutdown_kernel(now=True)
