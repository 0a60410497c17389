# SPDX-License-Identifier: MIT
# Ctrl-C (SIGINT) stops a run and raises Interrupted with the valid partial mesh; the GIL is
# released while C++ works.
import os
import signal
import threading
import time

import pytest

import tessera


@pytest.fixture(autouse=True)
def python_handles_sigint():
    """Python's own SIGINT handler, whatever the runner inherited: a shell without job control
    starts background commands with SIGINT ignored, and then Python installs no handler and
    tessera (which only takes over from Python's default handler) none either."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def interrupt_after(seconds: float) -> threading.Timer:
    timer = threading.Timer(seconds, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    return timer


@pytest.mark.parametrize("method, options", [
    ("front", {"step": 0.004}),
    ("atlas", {"tolerance": 1e-7}),
])
def test_ctrl_c_stops_a_catalogue_run(method, options):
    interrupt_after(0.3)
    started = time.monotonic()
    with pytest.raises(tessera.Interrupted) as error:
        tessera.mesh("torus", method=method, **options)
    assert time.monotonic() - started < 10  # the whole run would take minutes
    assert isinstance(error.value, KeyboardInterrupt)
    partial = error.value.mesh
    assert partial.termination == "interrupted" and partial.vertex_count > 0
    assert tessera.check(partial)["valid"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_ctrl_c_stops_a_python_problem(sphere):
    interrupt_after(0.3)
    with pytest.raises(tessera.Interrupted) as error:
        tessera.mesh(sphere, method="front", step=0.003, start=[0, 0, 1])
    assert error.value.mesh.vertex_count > 0
    assert tessera.check(error.value.mesh, sphere)["valid"]


def test_without_handling_the_interrupt_is_python_s():
    # handle_interrupt=False: Python's handler stays; the KeyboardInterrupt comes after the run.
    interrupt_after(0.05)
    with pytest.raises(KeyboardInterrupt) as error:
        tessera.mesh("sphere", method="front", step=0.03, handle_interrupt=False)
        time.sleep(1)  # the pending signal is raised at the next bytecode
    assert not isinstance(error.value, tessera.Interrupted)


def test_the_gil_is_released_while_cpp_works():
    counter = 0
    done = threading.Event()

    def count():
        nonlocal counter
        while not done.is_set():
            counter += 1

    worker = threading.Thread(target=count)
    worker.start()
    try:
        started = time.monotonic()
        tessera.mesh("torus", method="front", step=0.04)
        elapsed = time.monotonic() - started
        before = counter
        # The counter ran during the mesh at a good fraction of its free rate.
        time.sleep(0.2)
        rate_free = (counter - before) / 0.2
    finally:
        done.set()
        worker.join()
    assert elapsed > 0.1
    assert before > 0.2 * rate_free * elapsed


def press_ctrl_c(times: int):
    """A progress callback that presses Ctrl-C `times` times during the run, once."""
    pressed = []

    def progress(_):
        if not pressed:
            pressed.append(True)
            for _ in range(times):
                os.kill(os.getpid(), signal.SIGINT)

    return progress


def test_one_ctrl_c_is_one_interrupt():
    with pytest.raises(tessera.Interrupted) as error:
        tessera.mesh("torus", method="front", step=0.01, progress=press_ctrl_c(1))
    assert error.value.mesh.termination == "interrupted"
    time.sleep(0.05)  # no second KeyboardInterrupt is pending
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


@pytest.mark.parametrize("method", ["front", "atlas"])
def test_a_second_ctrl_c_follows_the_first_as_a_keyboard_interrupt(method):
    # The first Ctrl-C stops the build; the run then finishes what keeps the partial mesh valid
    # and cannot be cut shorter. A second one is not lost: it is raised where Python next
    # checks, i.e. in the handler of the first, as it would be in any Python code.
    partial = []
    with pytest.raises(KeyboardInterrupt) as second:
        try:
            tessera.mesh("torus", method=method, step=0.01, tolerance=1e-4,
                         progress=press_ctrl_c(2))
        except tessera.Interrupted as first:
            partial.append(first.mesh)
            time.sleep(0.01)
            pytest.fail("the second Ctrl-C was lost")
    assert not isinstance(second.value, tessera.Interrupted)
    assert isinstance(second.value.__context__, tessera.Interrupted)
    assert partial and partial[0].termination == "interrupted" and partial[0].vertex_count > 0
    assert tessera.check(partial[0])["valid"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_ctrl_c_stops_a_comparison():
    interrupt_after(0.3)
    started = time.monotonic()
    with pytest.raises(tessera.Interrupted) as error:
        tessera.compare("torus", tolerance=1e-7)
    assert time.monotonic() - started < 10
    rows = error.value.report["methods"]
    assert [row["method"] for row in rows] == tessera.methods()
    # The method running stops; the others stop at their first poll.
    assert all(row["termination"] == "interrupted" and row["valid"] for row in rows), rows
    assert rows[0]["vertex_count"] > 0 and not error.value.report["passes"]
