"""What several test files share: a small model with a closed form, and Ctrl-C sent to a call."""

import signal
import threading
import time
from collections.abc import Callable

import pytest

# x'' = -k x: from x = 1, v = 0, x = cos(2t) for k = 4.
OSCILLATOR = """
mod oscillator {
    params { k = 4.0 }
    states { x, v }
    equations {
        der(x) = v;
        der(v) = -k * x;
    }
    outputs {
        energy = v^2 / 2 + k * x^2 / 2;
    }
}
"""


def seconds_to_interrupt(call: Callable[[], object], after: float = 0.5) -> float:
    """Sends SIGINT `after` seconds into `call`; the seconds until it raised
    `KeyboardInterrupt` (the call must still run when the signal comes)."""
    sent: list[float] = []

    def interrupt() -> None:
        sent.append(time.monotonic())
        signal.raise_signal(signal.SIGINT)

    timer = threading.Timer(after, interrupt)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
        raised = time.monotonic()
    finally:
        timer.cancel()
    assert sent, "the call ended before the signal"
    return raised - sent[0]
