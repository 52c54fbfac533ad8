"""The latency helper calls what it is given (its times are never asserted)."""

from mechlib.timing import seconds_per_call


def test_the_call_gets_its_arguments_and_is_timed_number_times_per_repeat() -> None:
    calls: list[int] = []
    seconds = seconds_per_call(calls.append, 7, repeats=2, number=3)
    assert calls == [7] * 6 and seconds >= 0.0
