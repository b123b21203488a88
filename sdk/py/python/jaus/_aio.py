"""``asyncio`` over ``jaus.Watch``: the reports of a watch as an async iterator.

The watch's queue is read on the event loop's default executor, a short wait at a
time, so the loop never blocks and cancelling the task ends the wait promptly.
"""

import asyncio

# How long one executor call waits for a report (seconds).
_STEP = 0.2


class AsyncWatch:
    """The reports of a :class:`jaus.Watch` for ``async for``; ``async with`` (or
    :meth:`aclose`) ends the service connection or event."""

    def __init__(self, watch):
        self._watch = watch

    @property
    def watch(self):
        """The underlying :class:`jaus.Watch`."""
        return self._watch

    def __aiter__(self):
        return self

    async def __anext__(self):
        loop = asyncio.get_running_loop()
        while True:
            m = await loop.run_in_executor(None, self._watch.get, _STEP)
            if m is not None:
                return m
            if self._watch.closed:
                # Reports queued before the end are still delivered.
                m = self._watch.get(0)
                if m is None:
                    raise StopAsyncIteration
                return m

    async def aclose(self):
        """Ends the service connection or event."""
        self._watch.close()

    async def __aenter__(self):
        return self

    async def __aexit__(self, *exc):
        self._watch.close()
        return False
