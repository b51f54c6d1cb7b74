"""The one scheduler-address parser and connector shared by the explorer and the sweep runner."""

import pytest

from tvtrack.executors import SchedulerError, parse_scheduler_address


@pytest.mark.parametrize(
    "address, expected",
    [
        ("127.0.0.1:8786", ("127.0.0.1", 8786)),
        ("tcp://host:1", ("host", 1)),
        ("tls://host:65535/", ("host", 65535)),
        ("tcp://[::1]:8786", ("::1", 8786)),
    ],
)
def test_addresses_parse_to_host_and_port(address, expected):
    assert parse_scheduler_address(address) == expected


@pytest.mark.parametrize(
    "address, words",
    [
        ("localhost", "has no port"),
        ("tcp://host:", "has no port"),
        ("tcp://host:0", "not a number in [1, 65535]"),
        ("tcp://host:70000", "not a number in [1, 65535]"),
        ("tcp://host:http", "'http'"),
        ("udp://host:1", "scheme 'udp'"),
        ("a b:1", "not HOST:PORT"),
    ],
)
def test_bad_addresses_are_one_line_value_errors_naming_the_address(address, words):
    with pytest.raises(SchedulerError, match=None) as info:
        parse_scheduler_address(address)
    message = str(info.value)
    assert isinstance(info.value, ValueError) and "\n" not in message
    assert repr(address) in message and words in message
